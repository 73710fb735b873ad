#!/usr/bin/python3
"""Fits the /i/ targets of the /ai/ plan: the Δλ of GGp and SG (mm) that bring the landmarks to a
target posture at the end of experiments/ai.yaml, with scipy.optimize.least_squares.

The λ model runs in ep_controller, a process of its own, so every evaluation is a whole
run_experiment run with a changed plan (plan.delta_lambda_mm.<group>.1), on a udpm port of its
own. A finite-difference Jacobian's runs are submitted together, so they run in parallel on the
cluster. Every run lands in the output folder as a sweep row: a rerun of the fit takes the runs it
has from there (the closed loop in lock-step is deterministic) and goes on.

The target is the posture reached with --truth (default GGp -10, SG -20 mm, against the plan's
-15, -15): the fit should find about those. The residuals are the x and y displacements (mm) of
tip, palatal dorsum, velar dorsum and root from the first frame at 0.5 s.

Usage: PYTHONPATH=build/python:python /usr/bin/python3 python/examples/fit_i_plan.py
           [--out DIR] [--workers N | --scheduler tcp://HOST:8786] [--ports 7985-7994]
"""
import argparse
import os
import time

import numpy as np
from scipy.optimize import least_squares

from tongue_sweep import Sweep, dask_client, make_runs, parse_ports

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXPERIMENT = os.path.join(ROOT, "experiments", "ai.yaml")
GROUPS = ("GGp", "SG")
LANDMARKS = ("tip", "palatal_dorsum", "velar_dorsum", "root")
STEP_MM = 0.5  # finite-difference step of Δλ: well above the closed loop's numerical noise


def runs_for(points):
    return make_runs([{"experiment": EXPERIMENT,
                       **{f"plan.delta_lambda_mm.{g}.1": round(float(v), 6)
                          for g, v in zip(GROUPS, x)}} for x in points])


def posture_mm(row):
    if row["status"] != "ok":
        raise RuntimeError(f"run {row['key']} failed: {row['error']}")
    return np.array([1e3 * row[f"{name}_d{axis}_m"] for name in LANDMARKS for axis in "xy"])


class Evaluations:
    """Postures at Δλ points, each batch one sweep on the cluster; counts the runs done."""

    def __init__(self, sweep):
        self.sweep = sweep
        self.cache = {}
        self.runs = 0  # points evaluated
        self.on_record = 0  # of them, found done in the output folder

    def postures(self, points):
        todo = [p for p in points if tuple(p) not in self.cache]
        if todo:
            for p, row in zip(todo, self.sweep.run(runs_for(todo))):
                self.cache[tuple(p)] = posture_mm(row)
            self.runs += len(todo)
            self.on_record += self.sweep.skipped
        return [self.cache[tuple(p)] for p in points]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(ROOT, "logs", "fit_i_plan"))
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=2)
    where.add_argument("--scheduler")
    parser.add_argument("--ports", default="7985-7994")
    parser.add_argument("--start", type=float, nargs=2, default=[-15.0, -15.0],
                        metavar=("GGP", "SG"), help="first guess (mm): the plan's /i/ targets")
    parser.add_argument("--truth", type=float, nargs=2, default=[-10.0, -20.0],
                        metavar=("GGP", "SG"), help="the Δλ (mm) whose posture is the target")
    args = parser.parse_args()

    started = time.perf_counter()
    with dask_client(args.scheduler, args.workers) as client:
        evaluations = Evaluations(Sweep(args.out, client, parse_ports(args.ports)))
        target = evaluations.postures([tuple(args.truth)])[0]
        print("target posture (mm, x y of " + ", ".join(LANDMARKS) + "):",
              np.array2string(target, precision=2))

        def residuals(x):
            return evaluations.postures([tuple(x)])[0] - target

        def jacobian(x):
            # Forward differences, their runs submitted together; f(x) is cached by residuals.
            points = [tuple(x)]
            for i in range(len(x)):
                h = np.zeros(len(x))
                h[i] = STEP_MM
                points.append(tuple(np.asarray(x) + h))
            f0, *shifted = evaluations.postures(points)
            return np.column_stack([(f - f0) / STEP_MM for f in shifted])

        fit = least_squares(residuals, np.array(args.start), jac=jacobian,
                            bounds=([-30.0, -30.0], [5.0, 5.0]), x_scale=[5.0, 5.0],
                            xtol=1e-3, ftol=1e-4, max_nfev=20)
    wall = time.perf_counter() - started
    error = fit.fun  # mm, at the fitted point
    print(f"fitted /i/ Δλ: GGp {fit.x[0]:+.2f} mm, SG {fit.x[1]:+.2f} mm "
          f"(truth {args.truth[0]:+.2f}, {args.truth[1]:+.2f}; start {args.start[0]:+.2f}, "
          f"{args.start[1]:+.2f})")
    print(f"landmark error: RMS {np.sqrt(np.mean(error ** 2)):.3f} mm, largest "
          f"{np.abs(error).max():.3f} mm; {fit.nfev} residual and {fit.njev} Jacobian "
          f"evaluations, {evaluations.runs} runs ({evaluations.on_record} of them on record), "
          f"{wall:.1f} s wall; {fit.message}")


if __name__ == "__main__":
    main()
