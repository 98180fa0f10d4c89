"""Fig. 5: centre-line wave action after a step load, V = 50 m/s, L_x/L_y = 19.

Run python studies/fig5.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce fig5 --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("fig5"))
