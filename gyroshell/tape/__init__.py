"""The tape: its parameters (Table 1 by default, TOML files with units), the grid, the
finite-difference operators K, G, M from the discrete energy, loads (fixed, moving and
intermittent heads), damping, the model that assembles them, and its mirror symmetry.
"""
