#!/usr/bin/python3
"""A sweep on a local dask cluster against the same runs one after the other in this process:
40 runs of the SG 3 N scene (scenes/tongue_sg_3n.yaml) for 0.2 s simulated each (50 steps of
4 ms), SG and GGp levels varied, both through tongue_sweep.Sweep (rows written, table made), each
repeat into fresh output folders. Prints the medians over the repeats: sequential wall time,
sweep wall time, their ratio; the cluster's start-up, paid once per sweep command, apart. For
what the machine allows, the same runs also go to a plain multiprocessing pool of as many
processes (no dask, no rows written): the floor a sweep could reach here; and a plain CPU loop
done twice at once against once, in the same pool: what two busy processes get of this machine.
Where a sweep's time goes: the runs' own wall times summed (each row's wall_s) one after the
other, in the sweep and in the pool, and the CPU time this process (the scheduler, the client
and the rows) used during the sweep.

Usage: PYTHONPATH=build/python:python /usr/bin/python3 benchmarks/sweep_benchmark.py
           [--runs 40] [--duration 0.2] [--workers 2] [--repeats 3]
"""
import os

# One BLAS thread in every process, this one too (OpenBLAS reads it when it loads, with the
# module), as dask's workers have: the sequential runs are then faster than with OpenBLAS's
# default of a thread per core, whose second thread contends with the first.
os.environ.update(OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")

import argparse  # noqa: E402
import multiprocessing  # noqa: E402
import resource  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "python"))

from tongue_sweep import Sweep, dask_client, execute, make_runs  # noqa: E402

SCENE = os.path.normpath(os.path.join(HERE, "..", "scenes", "tongue_sg_3n.yaml"))


def the_runs(count, duration):
    sg = np.linspace(0.02, 0.125, (count + 1) // 2)
    params = [{"scene": SCENE, "duration_s": duration, "levels.SG": round(float(s), 6),
               "levels.GGp": ggp} for s in sg for ggp in (0.0, 0.05)]
    return make_runs(params[:count])


def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def runs_seconds(rows):
    """The runs' own wall times summed [s]."""
    return sum(r["wall_s"] for r in rows)


def timed_sweep(client, runs, folder):
    """Wall time [s], the runs' own time [s] and this process's CPU time [s] of one sweep."""
    cpu = cpu_seconds()
    start = time.perf_counter()
    rows = Sweep(folder, client).run(runs)
    wall = time.perf_counter() - start
    cpu = cpu_seconds() - cpu
    failed = [r for r in rows if r["status"] != "ok"]
    if failed:
        raise RuntimeError(f"{len(failed)} runs failed, first: {failed[0]['error']}")
    return wall, runs_seconds(rows), cpu


def warm_up(_):
    import tongue  # noqa: F401


def busy_loop(n):
    x = 0
    for i in range(n):
        x += i
    return x


def machine_pair_factor(pool, n=10_000_000):
    """Wall time of two CPU loops at once over twice one alone: 0.5 with two free cores."""
    start = time.perf_counter()
    pool.map(busy_loop, [n], chunksize=1)
    one = time.perf_counter() - start
    start = time.perf_counter()
    pool.map(busy_loop, [n, n], chunksize=1)
    return (time.perf_counter() - start) / (2 * one)


def timed_pool(pool, runs):
    """Wall time [s] and the runs' own time [s] of the runs in the pool."""
    start = time.perf_counter()
    rows = pool.map(execute, [r.params for r in runs], chunksize=1)
    wall = time.perf_counter() - start
    if any(r["status"] != "ok" for r in rows):
        raise RuntimeError("a run failed in the pool")
    return wall, runs_seconds(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=40)
    parser.add_argument("--duration", type=float, default=0.2, help="simulated s per run")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    runs = the_runs(args.runs, args.duration)

    start = time.perf_counter()
    with dask_client(workers=args.workers) as client:
        client.wait_for_workers(args.workers)
        startup = time.perf_counter() - start
        sequential, parallel, floor, pair = [], [], [], []
        runs_alone, runs_swept, runs_pooled, sweep_cpu = [], [], [], []
        with tempfile.TemporaryDirectory() as tmp, \
                multiprocessing.get_context("spawn").Pool(args.workers) as pool:
            pool.map(warm_up, range(args.workers))
            for k in range(args.repeats):
                # Interleaved, so that all see the same load from others on the machine.
                wall, own, _ = timed_sweep(None, runs, os.path.join(tmp, f"seq{k}"))
                sequential.append(wall)
                runs_alone.append(own)
                wall, own, cpu = timed_sweep(client, runs, os.path.join(tmp, f"par{k}"))
                parallel.append(wall)
                runs_swept.append(own)
                sweep_cpu.append(cpu)
                wall, own = timed_pool(pool, runs)
                floor.append(wall)
                runs_pooled.append(own)
                pair.append(machine_pair_factor(pool))
                print(f"repeat {k + 1}: sequential {sequential[-1]:.2f} s, "
                      f"sweep on {args.workers} workers {parallel[-1]:.2f} s "
                      f"({parallel[-1] / sequential[-1]:.2f}x), plain pool {floor[-1]:.2f} s "
                      f"({floor[-1] / sequential[-1]:.2f}x), two CPU loops at once {pair[-1]:.2f}x; "
                      f"the runs' own time {runs_alone[-1]:.2f} s one after the other, "
                      f"{runs_swept[-1]:.2f} s in the sweep, {runs_pooled[-1]:.2f} s in the pool; "
                      f"this process's CPU in the sweep {sweep_cpu[-1]:.2f} s", flush=True)
    seq, par = statistics.median(sequential), statistics.median(parallel)
    low = statistics.median(floor)
    # Each repeat's own ratio compares two runs made one after the other, under the same load
    # from others on the machine; the ratio of the medians may take them from different repeats.
    paired = [p / s for p, s in zip(parallel, sequential)]
    print(f"{args.runs} runs of {args.duration} s simulated, medians of {args.repeats}: "
          f"sequential {seq:.2f} s ({1e3 * seq / args.runs:.0f} ms a run), sweep on "
          f"{args.workers} workers {par:.2f} s: {par / seq:.2f}x the sequential time; the "
          f"repeats' own ratios {statistics.median(paired):.2f}x "
          f"({min(paired):.2f}-{max(paired):.2f}) "
          f"(plain pool {low:.2f} s, {low / seq:.2f}x; two CPU loops at once "
          f"{statistics.median(pair):.2f}x one after the other); cluster start-up "
          f"{startup:.2f} s (once per command)")
    swept = statistics.median(w / a for w, a in zip(runs_swept, runs_alone))
    pooled = statistics.median(p / a for p, a in zip(runs_pooled, runs_alone))
    print(f"where the sweep's time goes, medians: the runs' own time in the sweep {swept:.2f}x "
          f"theirs one after the other (in the pool {pooled:.2f}x); this process's CPU "
          f"{statistics.median(sweep_cpu):.2f} s a sweep (the scheduler, the client, the rows)")


if __name__ == "__main__":
    main()
