"""Fig. 3: 3-D wire frames of the tape after a step load, V = 0 m/s, L_x/L_y = 4.

Run: python studies/fig3.py [--out DIR] [--quick]   (same as: gyroshell reproduce fig3 --out DIR)
"""

import sys

from gyroshell.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--out" not in args:
        args += ["--out", "results"]
    sys.exit(main(["reproduce", "fig3", *args]))
