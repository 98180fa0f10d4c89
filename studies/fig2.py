"""Fig. 2: transient load-point displacement for V = 0, 50, 90, 100 m/s, L_x/L_y = 19.

Run python studies/fig2.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce fig2 --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("fig2"))
