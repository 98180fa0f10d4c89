"""Head-tape air bearing: spacing against speed, 2-D maps, cross-width profile, tension step.

Run python studies/bearing.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce bearing --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("bearing"))
