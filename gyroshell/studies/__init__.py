"""Analyses built on the engines: speed sweeps, Campbell diagrams (one branch tracker),
parameter studies on local processes or a Dask cluster, stability classes, signal analysis.
"""
