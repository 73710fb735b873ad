#!/usr/bin/python3
"""What the Python module adds to a step: SG 3 N + relaxation (scenes/tongue_sg_3n_relax.yaml,
80 steps of 4 ms) stepped from Python, the wall time of each call against the C++ step inside it
(StepFigures.wall_seconds, SceneRun::step). Prints the medians over the runs, in microseconds
and as a share of the C++ step.

Usage: PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_step_benchmark.py [--runs N]
"""
import argparse
import os
import statistics
import time

import numpy as np

import tongue

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "scenes", "tongue_sg_3n_relax.yaml")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    sim = tongue.Simulation(SCENE)
    sg = [i for i, name in enumerate(sim.muscle_names) if name.startswith("SG_")]
    on = np.zeros(len(sim.muscle_names))
    on[sg] = 3.0 / sim.max_forces[sg].sum()  # 3 N over SG, as the scene's schedule
    off = np.zeros(len(sim.muscle_names))
    steps = 80
    shares, added = [], []
    for _ in range(args.runs):
        sim.reset()
        python_s = cxx_s = 0.0
        for k in range(1, steps + 1):
            levels = on if k * sim.dt <= 0.12 + 1e-9 else off
            start = time.perf_counter()
            figures = sim.step(levels)
            python_s += time.perf_counter() - start
            cxx_s += figures.wall_seconds
        added.append((python_s - cxx_s) / steps)
        shares.append((python_s - cxx_s) / cxx_s)
    print(f"{args.runs} runs of {steps} steps: C++ step {1e3 * cxx_s / steps:.3f} ms (last run), "
          f"added by Python {1e6 * statistics.median(added):.1f} us a step, "
          f"{100 * statistics.median(shares):.2f} % of the C++ step (medians)")


if __name__ == "__main__":
    main()
