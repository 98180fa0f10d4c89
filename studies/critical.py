"""Critical-speed table: this model (free and simply supported edges, L_x/L_y = 4 and 19)

Run python studies/critical.py [--out DIR] [--quick], the same as
gyroshell reproduce critical --out DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("critical"))
