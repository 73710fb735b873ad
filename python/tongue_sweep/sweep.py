"""The sweep: the runs not yet done, on a dask cluster (or in this process), each row written to
the output folder as its run (or its task of several short runs) comes back, then the table."""
import bisect
import math
import os
from collections import deque

from .jobs import execute, execute_batch
from .ports import PortPool
from .store import RowStore, write_csv, write_hdf5

DEFAULT_PORTS = range(7985, 7995)
# Wall time a cluster task aims at [s]: runs shorter than this go several to a task, so that a
# task's own cost stays small beside it (no-op tasks on a local cluster of two workers took 2-3
# ms of wall time each on a 2-core machine: 5 % of a 50 ms run).
TASK_TARGET_S = 0.25
IGNORE_MODULES = "distributed.diagnostics.computations.ignore-modules"


def runs_per_task(queued, slots, walls):
    """How many runs the next task takes: one until a run's wall time is known, then enough to
    last about TASK_TARGET_S, but never more than an equal share of what is left between the
    worker threads (guided self-scheduling, Polychronopoulos & Kuck 1987: shares shrink as the
    queue does, so that every worker stays busy to the end). `walls`: the wall times of the runs
    done so far [s], sorted."""
    if not walls:
        return 1
    n = len(walls)
    median = walls[n // 2] if n % 2 else 0.5 * (walls[n // 2 - 1] + walls[n // 2])
    wanted = math.ceil(TASK_TARGET_S / max(median, 1e-3))
    return max(1, min(wanted, math.ceil(queued / slots)))


class Sweep:
    """Runs go to `client` (a distributed.Client), or run here one after the other when it is
    None. `on_row(row, done, total)` is called after each row is on disk."""

    def __init__(self, out_dir, client=None, ports=DEFAULT_PORTS, runner=None, on_row=None,
                 hdf5=False):
        self.store = RowStore(out_dir)
        self.client = client
        self.ports = list(ports)
        self.runner = runner
        self.on_row = on_row
        self.hdf5 = hdf5
        self.skipped = 0  # rows found done on the last run()
        self.tasks = 0  # cluster tasks the last run() sent (several short runs may share one)

    @property
    def table_path(self):
        return os.path.join(self.store.out_dir, "results.csv")

    def _logs_dir(self, run):
        return os.path.join(self.store.out_dir, "experiments", run.key)

    def _finish(self, runs, results, done, counter):
        """The runs' rows into `done` and onto disk (one folder sync for them all)."""
        rows = []
        for run, result in zip(runs, results):
            row = {"key": run.key, "kind": run.kind, **run.params, **result}
            row["key"], row["kind"] = run.key, run.kind  # a parameter may not shadow them
            rows.append(row)
        self.store.write(rows)
        for row in rows:
            done[row["key"]] = row
            counter[0] += 1
            if self.on_row:
                self.on_row(row, counter[0], counter[1])

    def run(self, runs):
        """Does the runs not on record as ok (failed ones again) and returns every run's row,
        in the runs' order. The table is rewritten even when this is interrupted."""
        done = self.store.load()
        pending = [r for r in runs if done.get(r.key, {}).get("status") != "ok"]
        self.skipped = len(runs) - len(pending)
        self.tasks = 0
        counter = [self.skipped, len(runs)]
        try:
            if self.client is None:
                for run in pending:
                    port = self.ports[0] if self.ports else None
                    results = execute(run.params, port, self._logs_dir(run), self.runner)
                    self._finish([run], [results], done, counter)
            else:
                import dask
                # At every submit dask reads the source of the calling function for its
                # dashboard's record of computations (distributed.Client._get_computation_code):
                # about 2 ms of this process's CPU a task, beside two workers on a small machine.
                # Every module counted as a library's, nothing is read.
                with dask.config.set({IGNORE_MODULES: [".*"]}):
                    self._run_on_cluster(pending, done, counter)
        finally:
            write_csv(self.table_path, runs, done)
            if self.hdf5:
                write_hdf5(os.path.join(self.store.out_dir, "results.h5"), runs, done)
        return [done[r.key] for r in runs]

    def _run_on_cluster(self, pending, done, counter):
        from distributed import as_completed
        ports = PortPool(self.ports)
        queue = deque(pending)
        in_flight = {}
        completed = as_completed()
        slots = max(1, sum(self.client.nthreads().values()))
        walls = []  # of the runs done so far [s], kept sorted

        def submit_what_can_go():
            # Two tasks per worker thread, one running and one waiting its turn on the worker;
            # but one each until a run's wall time is known, the second would be a single run too.
            while queue and len(in_flight) < (2 * slots if walls else slots):
                # An experiment needs a free port; while every port is in use, the runs queued
                # behind it that need none go first.
                first = next((i for i, r in enumerate(queue)
                              if r.kind != "experiment" or ports.free), None)
                if first is None:
                    return
                queue.rotate(-first)
                kind = queue[0].kind
                port = ports.take() if kind == "experiment" else None
                size = runs_per_task(len(queue), slots, walls)
                batch = []
                while queue and len(batch) < size and queue[0].kind == kind:
                    batch.append(queue.popleft())
                future = self.client.submit(
                    execute_batch, [(r.params, self._logs_dir(r)) for r in batch], port,
                    self.runner, pure=False, retries=0)
                in_flight[future] = (batch, port)
                self.tasks += 1
                completed.add(future)

        submit_what_can_go()
        try:
            for future in completed:
                batch, port = in_flight.pop(future)
                try:
                    results = future.result()
                except Exception as e:  # noqa: BLE001 - e.g. the worker died (KilledWorker)
                    failed = {"status": "failed", "error": f"{type(e).__name__}: {e}"}
                    results = [failed] * len(batch)
                ports.give_back(port)
                for result in results:
                    if "wall_s" in result:
                        bisect.insort(walls, result["wall_s"])
                submit_what_can_go()  # before the rows go to disk: no worker waits for that
                self._finish(batch, results, done, counter)
        finally:
            if in_flight:
                self.client.cancel(list(in_flight))
