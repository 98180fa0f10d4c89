"""Imported by the fork server of the reproductions' workers (``_runner.PRELOAD``):
matplotlib on its Agg back-end with pyplot, once for all the workers, which only write
figures to files."""

from __future__ import annotations

from ._common import pyplot

pyplot()
