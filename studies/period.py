"""Dominant period of the load-point displacement against tape speed, L_x/L_y = 19.

Run:
    python studies/period.py [--out DIR] [--quick]
Same as: gyroshell reproduce period --out DIR
"""

import sys

from gyroshell.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--out" not in args:
        args += ["--out", "results"]
    sys.exit(main(["reproduce", "period", *args]))
