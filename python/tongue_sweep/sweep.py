"""The sweep: the runs not yet done, on a dask cluster (or in this process), each finished row
written to the output folder as it comes, then the table."""
import os
from collections import deque

from .jobs import execute
from .ports import PortPool
from .store import RowStore, write_csv, write_hdf5

DEFAULT_PORTS = range(7985, 7995)


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

    @property
    def table_path(self):
        return os.path.join(self.store.out_dir, "results.csv")

    def _logs_dir(self, run):
        return os.path.join(self.store.out_dir, "experiments", run.key)

    def _finish(self, run, results, counter):
        row = {"key": run.key, "kind": run.kind, **run.params, **results}
        row["key"], row["kind"] = run.key, run.kind  # a parameter may not shadow them
        self.store.write(row)
        counter[0] += 1
        if self.on_row:
            self.on_row(row, counter[0], counter[1])
        return row

    def run(self, runs):
        """Does the runs not on record as ok (failed ones again) and returns every run's row,
        in the runs' order. The table is rewritten even when this is interrupted."""
        done = self.store.load()
        pending = [r for r in runs if done.get(r.key, {}).get("status") != "ok"]
        self.skipped = len(runs) - len(pending)
        counter = [self.skipped, len(runs)]
        try:
            if self.client is None:
                for run in pending:
                    port = self.ports[0] if self.ports else None
                    results = execute(run.params, port, self._logs_dir(run), self.runner)
                    done[run.key] = self._finish(run, results, counter)
            else:
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

        def submit_what_can_go():
            waiting = deque()
            while queue:
                run = queue.popleft()
                port = None
                if run.kind == "experiment":
                    port = ports.take()
                    if port is None:  # every port is in use: wait for one
                        waiting.append(run)
                        continue
                future = self.client.submit(execute, run.params, port, self._logs_dir(run),
                                            self.runner, pure=False, retries=0)
                in_flight[future] = (run, port)
                completed.add(future)
            queue.extend(waiting)

        submit_what_can_go()
        try:
            for future in completed:
                run, port = in_flight.pop(future)
                try:
                    results = future.result()
                except Exception as e:  # noqa: BLE001 - e.g. the worker died (KilledWorker)
                    results = {"status": "failed", "error": f"{type(e).__name__}: {e}"}
                ports.give_back(port)
                done[run.key] = self._finish(run, results, counter)
                submit_what_can_go()
        finally:
            if in_flight:
                self.client.cancel(list(in_flight))
