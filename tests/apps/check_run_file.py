#!/usr/bin/env python3
"""Runs sim_batch on a small scene and opens the run file with h5py, as a user would.

Usage: check_run_file.py PATH/TO/sim_batch
Exits 0 when the file has the documented layout, units and contents; prints what is wrong otherwise.
"""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

SCENE = """
mesh:
  box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}   # 20 nodes, 4 hex8
material: {type: mooney_rivlin5}
constraints:
  - {set: x_min, components: [x, y, z]}
gravity: [0, -9.81, 0]
analysis: {type: dynamic, duration: 0.01, dt: 0.002}
"""


def check(condition, what):
    if not condition:
        print("FAILED:", what)
        sys.exit(1)


def main():
    sim_batch = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        h5 = os.path.join(tmp, "run.h5")
        run = subprocess.run([sim_batch, scene, "--output", h5, "--quiet"],
                             capture_output=True, text=True)
        check(run.returncode == 0, "sim_batch exit code %d: %s" % (run.returncode, run.stderr))

        with h5py.File(h5, "r") as f:
            frames = 6  # t = 0 and 5 steps
            check(f["time"].shape == (frames,), "/time shape %s" % (f["time"].shape,))
            check(f["positions"].shape == (frames, 20, 3),
                  "/positions shape %s" % (f["positions"].shape,))
            check(f["rest_positions"].shape == (20, 3), "/rest_positions shape")
            check(f["elements"].shape == (4, 8), "/elements shape")
            for name in ("iterations", "residual", "wall_time", "cuts"):
                check(f["solver"][name].shape == (frames,), "/solver/%s shape" % name)
            check(np.allclose(f["time"][:], np.arange(frames) * 0.002), "/time values")
            rest = f["rest_positions"][:]
            check(np.array_equal(f["positions"][0], rest), "first frame is the rest state")
            check(np.abs(f["positions"][-1] - rest).max() > 1e-6, "last frame moved")
            check(f["elements"][:].min() == 0 and f["elements"][:].max() == 19,
                  "element node indices are 0-based")
            # Attributes: variable-length strings come back as str.
            check(f.attrs["format_version"] == 1, "format_version")
            check(f.attrs["length_unit"] == "m", "length_unit")
            check(f.attrs["scene_text"] == SCENE, "scene_text")
            check(f.attrs["status"] == "completed", "status")
            for name, unit in (("time", "s"), ("positions", "m"), ("rest_positions", "m"),
                               ("solver/residual", "N"), ("solver/wall_time", "s")):
                check(f[name].attrs["units"] == unit, "units of /%s" % name)
            check(f["positions"].chunks is not None and f["positions"].maxshape[0] is None,
                  "/positions is chunked and extendible along time")
    print("run file OK")


if __name__ == "__main__":
    main()
