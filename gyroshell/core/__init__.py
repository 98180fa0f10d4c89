"""Services every layer uses: errors, parameter checks, the memory budget, atomic output
files, the progress bar, process pools and BLAS threads, the unit table, the version.

The lowest layer: it imports nothing else of gyroshell.
"""
