"""The paper's other observations, measured.

Run python studies/observations.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce observations --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("observations"))
