"""Sweeps of tongue simulations on a dask cluster: many runs, one table (docs/sweeps.md)."""
from .cluster import dask_client
from .definition import Run, make_runs, read_sweep
from .jobs import execute
from .ports import parse_ports
from .sweep import Sweep

__all__ = ["Run", "Sweep", "dask_client", "execute", "make_runs", "parse_ports", "read_sweep"]
