"""Helical scan: a two-head drum crossing the tape obliquely with intermittent contact.

Run python studies/helical.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce helical --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("helical"))
