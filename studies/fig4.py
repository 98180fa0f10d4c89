"""Fig. 4: 3-D wire frames of the tape after a step load, V = 50 m/s, L_x/L_y = 4.

Run python studies/fig4.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce fig4 --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("fig4"))
