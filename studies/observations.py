"""The paper's other observations, measured.

Run:
    python studies/observations.py [--out DIR] [--quick]
Same as: gyroshell reproduce observations --out DIR
"""

import sys

from gyroshell.cli import main

if __name__ == "__main__":
    args = sys.argv[1:]
    if "--out" not in args:
        args += ["--out", "results"]
    sys.exit(main(["reproduce", "observations", *args]))
