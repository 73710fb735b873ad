"""Shared by the sweep tests: the project's folders, tongue_sweep importable (CTest puts python/
on PYTHONPATH; by hand it is found from here), and one local cluster of two workers."""
import os
import sys

import pytest

PROJECT = os.environ.get("PROJECT_DIR") or os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(__file__)))))
sys.path.insert(0, os.path.join(PROJECT, "python"))

from tongue_sweep import dask_client  # noqa: E402

SG_3N = os.path.join(PROJECT, "scenes", "tongue_sg_3n.yaml")
AI = os.path.join(PROJECT, "experiments", "ai.yaml")
# Columns that differ between two runs of the same sweep: where and how long it ran.
UNREPEATABLE = {"worker", "wall_s", "physics_wall_s", "port", "run_folder"}


def repeatable(rows):
    return [{k: v for k, v in row.items() if k not in UNREPEATABLE} for row in rows]


@pytest.fixture(scope="session")
def client():
    with dask_client(workers=2) as c:
        yield c


def pytest_configure(config):
    # Debian's tornado warns about its own event-loop call inside distributed; not ours to fix.
    config.addinivalue_line("filterwarnings", "ignore:make_current is deprecated:DeprecationWarning")
