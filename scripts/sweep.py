#!/usr/bin/python3
"""Runs a sweep (python/tongue_sweep; docs/sweeps.md) without setting PYTHONPATH by hand:
python/ of this checkout is added, and build/python when the tongue module is not importable.

Usage: /usr/bin/python3 scripts/sweep.py SWEEP_FILE --out DIR [--workers N |
       --scheduler tcp://HOST:8786 | --sequential] [--ports 7985-7994] [--hdf5]
"""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
try:
    import tongue  # noqa: F401
except ImportError:
    sys.path.insert(0, os.path.join(ROOT, "build", "python"))

from tongue_sweep.__main__ import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
