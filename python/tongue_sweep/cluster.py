"""A dask client: a LocalCluster of worker processes with one thread each (a step holds a core;
a thread more per process would only contend), or an existing scheduler."""
import contextlib
import logging
import os
import sys


def _export_python_path():
    """LocalCluster's workers must import tongue and tongue_sweep as this process does."""
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    paths = [here]
    try:
        import tongue
        paths.append(os.path.dirname(os.path.abspath(tongue.__file__)))
    except ImportError:
        pass
    current = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    os.environ["PYTHONPATH"] = os.pathsep.join(paths + [p for p in current if p not in paths])
    for p in paths:
        if p not in sys.path:
            sys.path.insert(0, p)


@contextlib.contextmanager
def dask_client(scheduler=None, workers=2):
    import dask
    from distributed import Client, LocalCluster
    if scheduler:
        client = Client(scheduler)
        try:
            yield client
        finally:
            client.close()
        return
    _export_python_path()
    # The workers' environment as dask sets it (one BLAS thread each) but for its
    # MALLOC_TRIM_THRESHOLD_ of 64 KiB, with which glibc hands freed memory back to the system
    # so eagerly that tongue runs were 10-20 % slower (40 SG runs on two workers: 2.39-2.53 s
    # with it, 2.06-2.11 s without; benchmarks/sweep_benchmark.py, alternating).
    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ"))
    environ.pop("MALLOC_TRIM_THRESHOLD_", None)
    # The workers' own monitors, sampled less often: the statistical profiler (every 10 ms by
    # default; nothing here reads it), the memory check (100 ms) and the system monitor (500 ms)
    # take CPU beside the runs on a small machine (40 short runs on two workers, 8 sweeps each
    # way alternating: median 1.96 s with these settings against 2.09 s with dask's defaults).
    # The event loops' tick (every 20 ms by default, a watchdog for blocked loops) every second,
    # and no work stealing: with dask's task queuing a worker holds at most two tasks, so there
    # is nothing to rebalance, and the stealing's bookkeeping runs on the scheduler, which shares
    # this machine's cores with the workers (this process used 0.26-0.30 s of CPU a sweep of
    # the 40 runs with these two settings, 0.32-0.42 s without).
    dask.config.set({"distributed.nanny.pre-spawn-environ": environ,
                     "distributed.worker.profile.enabled": False,
                     "distributed.worker.memory.monitor-interval": "1s",
                     "distributed.admin.system-monitor.interval": "5s",
                     "distributed.admin.tick.interval": "1s",
                     "distributed.scheduler.work-stealing": False})
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=logging.CRITICAL)
    client = Client(cluster)
    try:
        yield client
    finally:
        client.close()
        cluster.close()
