"""Critical-speed table: this model (free and simply supported edges, L_x/L_y = 4 and 19)

Run python studies/critical.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce critical --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("critical"))
