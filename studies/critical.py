"""Critical-speed table: this model (free and simply supported edges, L_x/L_y = 4 and 19)

Run:
    python studies/critical.py [--out DIR] [--quick]
Same as: gyroshell reproduce critical --out DIR
"""

import sys

from gyroshell.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--out" not in args:
        args += ["--out", "results"]
    sys.exit(main(["reproduce", "critical", *args]))
