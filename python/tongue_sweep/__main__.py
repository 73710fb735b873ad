"""python -m tongue_sweep SWEEP_FILE --out DIR [options]: the command line (docs/sweeps.md)."""
import argparse
import sys

from .cluster import dask_client
from .definition import read_sweep
from .ports import parse_ports
from .sweep import Sweep


def parse_arguments(argv):
    p = argparse.ArgumentParser(prog="tongue_sweep",
                                description="Run a sweep of tongue simulations on dask.")
    p.add_argument("sweep", help="the sweep file (.yaml or .csv)")
    p.add_argument("--out", required=True, help="output folder (rows, table, experiment logs)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=2,
                       help="worker processes of the local cluster (default 2)")
    where.add_argument("--scheduler", help="an existing cluster, e.g. tcp://HOST:8786")
    where.add_argument("--sequential", action="store_true",
                       help="no cluster: the runs one after the other in this process")
    p.add_argument("--ports", default="7985-7994",
                   help="udpm ports for experiment runs, one per run in flight (default 7985-7994)")
    p.add_argument("--run-experiment", help="the runner program (default: next to the module)")
    p.add_argument("--hdf5", action="store_true", help="also write results.h5")
    p.add_argument("--quiet", action="store_true", help="no line per run")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_arguments(argv)
    runs = read_sweep(args.sweep)

    def report(row, done, total):
        if not args.quiet:
            what = row["error"] if row["status"] != "ok" else f"{row['wall_s']:.2f} s"
            print(f"[{done}/{total}] {row['key']} {row['status']}: {what}", flush=True)

    def sweep_with(client):
        sweep = Sweep(args.out, client, parse_ports(args.ports), args.run_experiment, report,
                      args.hdf5)
        rows = sweep.run(runs)
        return sweep, rows

    if args.sequential:
        sweep, rows = sweep_with(None)
    else:
        with dask_client(args.scheduler, args.workers) as client:
            sweep, rows = sweep_with(client)
    failed = sum(r["status"] != "ok" for r in rows)
    print(f"{len(rows)} runs: {sweep.skipped} done before, {len(rows) - sweep.skipped} now, "
          f"{failed} failed; table {sweep.table_path}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
