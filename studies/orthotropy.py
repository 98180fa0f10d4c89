"""Orthotropic tapes: critical speed, frequencies, profiles and bearing spacing against E_y/E_x.

Run python studies/orthotropy.py [--out-dir DIR] [--quick], the same as
gyroshell reproduce orthotropy --out-dir DIR (default DIR: results).
"""

from gyroshell.cli.reproduce import script

if __name__ == "__main__":
    raise SystemExit(script("orthotropy"))
