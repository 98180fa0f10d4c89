"""Fig. 4: 3-D wire frames of the tape after a step load, V = 50 m/s, L_x/L_y = 4.

Run: python studies/fig4.py [--out DIR] [--quick]   (same as: gyroshell reproduce fig4 --out DIR)
"""

import sys

from gyroshell.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--out" not in args:
        args += ["--out", "results"]
    sys.exit(main(["reproduce", "fig4", *args]))
