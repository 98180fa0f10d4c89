"""Flat heads: spacing and pressure along a three-module head, the read line across the
width against speed, a wrap-angle map of read-line spacing and drag.

Run python studies/heads.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce heads --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("heads"))
