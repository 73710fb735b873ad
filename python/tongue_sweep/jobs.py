"""The function every worker runs: one run, its error caught into its row so that a failing run
never ends the sweep."""
import os
import socket
import time
import traceback

from .experiment_job import run_experiment
from .simulation_job import run_simulation


def execute_batch(batch, port=None, runner=None):
    """execute() for each (params, logs_dir) of batch in turn, on one port: one dask task for
    several short runs, whose own cost (a few ms each way) would otherwise weigh on them."""
    return [execute(params, port, logs_dir, runner) for params, logs_dir in batch]


def execute(params, port=None, logs_dir=None, runner=None):
    """The results part of a run's row (status, error, figures, worker, wall_s)."""
    start = time.perf_counter()
    try:
        if params["kind"] == "simulation":
            results = run_simulation(params)
        else:
            results = run_experiment(params, port, logs_dir, runner)
        status, error = "ok", ""
    except Exception as e:  # noqa: BLE001 - any failure belongs in the row
        results, status = {}, "failed"
        error = f"{type(e).__name__}: {e}"
        if not str(e):
            error += " " + traceback.format_exc(limit=3).replace("\n", " | ")
    return {"status": status, "error": error, **results,
            "worker": f"{socket.gethostname()}:{os.getpid()}",
            "wall_s": time.perf_counter() - start}
