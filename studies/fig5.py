"""Fig. 5: centre-line wave action after a step load, V = 50 m/s, L_x/L_y = 19.

Run: python studies/fig5.py [--out DIR] [--quick]   (same as: gyroshell reproduce fig5 --out DIR)
"""

import sys

from gyroshell.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--out" not in args:
        args += ["--out", "results"]
    sys.exit(main(["reproduce", "fig5", *args]))
