#!/usr/bin/python3
"""Nodal error of a run against a reference run of the same mesh: at every time both files have
(to 1e-9 s), the distance between each node's positions; prints the RMS over all nodes and those
times, the largest distance (where and when), and the same at the landmarks.

usage: /usr/bin/python3 scripts/compare_runs.py RUN.h5 REFERENCE.h5

Exit status: 0 compared; 1 the files cannot be compared (missing, different meshes, no common
time). Distances are in mm, times in s.
"""
import argparse
import sys

import h5py
import numpy as np

import run_file

TIME_TOLERANCE = 1e-9  # s: frame times are sums of dt and carry round-off


def common_frames(t_run, t_ref):
    """Index pairs (i in run, j in reference) of the times both have."""
    j = np.searchsorted(t_ref, t_run)
    pairs = []
    for i, k in enumerate(j):
        for candidate in (k - 1, k):
            if 0 <= candidate < len(t_ref) and abs(t_ref[candidate] - t_run[i]) <= TIME_TOLERANCE:
                pairs.append((i, candidate))
                break
    return pairs


def compare(run_path, reference_path):
    with h5py.File(run_path, "r") as run, h5py.File(reference_path, "r") as ref:
        for name, h5 in ((run_path, run), (reference_path, ref)):
            for d in ("time", "positions", "rest_positions"):
                if d not in h5:
                    raise run_file.RunError("%s has no dataset /%s" % (name, d))
        if run["rest_positions"].shape != ref["rest_positions"].shape or not np.array_equal(
                run["rest_positions"][()], ref["rest_positions"][()]):
            raise run_file.RunError("%s and %s are not runs of the same mesh"
                                    % (run_path, reference_path))
        pairs = common_frames(run["time"][()], ref["time"][()])
        if not pairs:
            raise run_file.RunError("%s and %s have no time in common" % (run_path, reference_path))
        t = run["time"][()]
        landmarks = {}
        for name in run_file.LANDMARKS:
            path = "mesh/node_sets/" + name
            if path in run and len(run[path]) > 0:
                landmarks[name] = int(run[path][0])
        squares, count = 0.0, 0
        worst = (0.0, 0, 0.0)  # mm, node, s
        landmark_max = {name: 0.0 for name in landmarks}
        for i, j in pairs:
            d = 1e3 * np.linalg.norm(run["positions"][i] - ref["positions"][j], axis=1)  # mm
            squares += float(np.sum(d * d))
            count += d.size
            k = int(np.argmax(d))
            if d[k] > worst[0]:
                worst = (float(d[k]), k, float(t[i]))
            for name, node in landmarks.items():
                landmark_max[name] = max(landmark_max[name], float(d[node]))
        return {"frames": len(pairs), "rms": (squares / count) ** 0.5, "max": worst[0],
                "max_node": worst[1], "max_time": worst[2], "landmarks": landmark_max}


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run")
    parser.add_argument("reference")
    args = parser.parse_args(argv)
    try:
        r = compare(args.run, args.reference)
    except (run_file.RunError, OSError) as e:
        print("compare_runs: %s" % e, file=sys.stderr)
        return 1
    print("%s against %s: %d common frames" % (args.run, args.reference, r["frames"]))
    print("nodal error: RMS %.4f mm, max %.4f mm (node %d at t = %.4f s)"
          % (r["rms"], r["max"], r["max_node"], r["max_time"]))
    for name, value in r["landmarks"].items():
        print("  %-15s max %.4f mm" % (name, value))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
