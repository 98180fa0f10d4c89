"""The one result protocol (``base``) and the result kinds of the engines.

Every result saves (NetCDF; CSV / Parquet for tables), converts (``to_xarray``,
``to_frame``), summarizes (what ``--json`` prints) and plots itself the same way; see
:mod:`gyroshell.results.base`.
"""
