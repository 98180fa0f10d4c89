"""Dominant period of the load-point displacement against tape speed, L_x/L_y = 19.

Run python studies/period.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce period --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("period"))
