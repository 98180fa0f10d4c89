"""Fig. 3: 3-D wire frames of the tape after a step load, V = 0 m/s, L_x/L_y = 4.

Run python studies/fig3.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce fig3 --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("fig3"))
