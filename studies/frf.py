"""Frequency response (Bode) at V = 0, 50 and 90 m/s: resonances move down with speed.

Run python studies/frf.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce frf --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("frf"))
