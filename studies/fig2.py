"""Fig. 2: transient load-point displacement for V = 0, 50, 90, 100 m/s, L_x/L_y = 19.

Run: python studies/fig2.py [--out DIR] [--quick]   (same as: gyroshell reproduce fig2 --out DIR)
"""

import sys

from gyroshell.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--out" not in args:
        args += ["--out", "results"]
    sys.exit(main(["reproduce", "fig2", *args]))
