#!/usr/bin/python3
"""Integration test of scripts/plot_run.py.

usage: test_plot_run.py PATH/TO/plot_run.py PATH/TO/sim_batch

A real run file: sim_batch runs a short built-in tongue scene (6 steps of 4 ms, the styloglossus
on from 2 to 14 ms); the script plots it, and the CSV it writes holds exactly the log's landmark
positions and muscle series. Small synthetic run files (a box straddling z = 0, written with h5py)
check the skipping of plots a log has no data for and the errors.
Run with Debian's Python (python3-h5py, python3-numpy, python3-matplotlib).
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

SCRIPT = None
SIM_BATCH = None
PICTURES = ["landmarks", "muscles", "shapes"]

TONGUE_SCENE = """
mesh:
  tongue: {refinement: 1}
material:
  type: mooney_rivlin5
  parameters: {poisson_ratio: 0.49}
constraints:
  - {set: mandible, components: [x, y, z]}
  - {set: root_bottom, components: [y]}
  - {set: hyoid, components: [y, z]}
gravity: [0, -9.81, 0]
damping: {beta: 0.028}
muscles: builtin
activations:
  - {group: SG, force: 3.0, start: 0.002, end: 0.014}
analysis: {type: dynamic, duration: 0.024, dt: 0.004}
"""


def run_script(*args):
    return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True,
                          timeout=300)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    values = np.array([[float(v) for v in row] for row in rows[1:]])
    return {name: values[:, i] for i, name in enumerate(header)}


def check_picture(test, png):
    test.assertTrue(os.path.isfile(png), png)
    image = mpimg.imread(png)  # fails on a file that is not a valid PNG
    test.assertEqual(image.ndim, 3, png)
    test.assertGreater(image.shape[0], 300, png)
    test.assertGreater(image.shape[1], 300, png)
    test.assertGreater(float(np.std(image[..., :3])), 0.05, "%s is blank" % png)


def write_box_run(path, landmarks=True, muscles=True, active=True, crossing=True):
    """A 2 x 2 x 2 box of hex8 (10 mm), 3 frames; z from -5 to 5 mm (crossing z = 0) or not."""
    n, h = 2, 0.005
    z0 = -0.005 if crossing else 0.001
    rest = np.array([(i * h, j * h, z0 + k * h) for k in range(n + 1) for j in range(n + 1)
                     for i in range(n + 1)])
    idx = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)  # noqa: E731
    elements = np.array([[idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
                          idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1),
                          idx(i, j + 1, k + 1)]
                         for k in range(n) for j in range(n) for i in range(n)], np.int32)
    frames = [rest + s * np.column_stack([-0.2 * rest[:, 1], 0.1 * rest[:, 1], 0 * rest[:, 1]])
              for s in (0.0, 0.5, 1.0)]
    with h5py.File(path, "w") as f:
        f["/rest_positions"] = rest
        f["/elements"] = elements
        f["/time"] = np.array([0.0, 0.002, 0.004])
        f["/positions"] = np.stack(frames)
        if landmarks:
            f["/mesh/node_sets/tip"] = np.array([idx(2, 2, 1)], np.int32)
            f["/mesh/node_sets/root"] = np.array([idx(0, 2, 1)], np.int32)
        if muscles:
            f["/muscles/names"] = np.array(["a", "b"], dtype=h5py.string_dtype())
            f["/muscles/max_force"] = np.array([2.0, 3.0])
            level = 0.5 if active else 0.0
            f["/activations"] = np.array([[0.0, 0.0], [level, 0.0], [level, 0.0]])


class RealTongueRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="plot_run_tongue_")
        cls.dir = cls.tmp.name
        scene = os.path.join(cls.dir, "scene.yaml")
        with open(scene, "w") as f:
            f.write(TONGUE_SCENE)
        cls.run_path = os.path.join(cls.dir, "tongue.h5")
        result = subprocess.run([SIM_BATCH, scene, "--output", cls.run_path, "--quiet"],
                                capture_output=True, text=True, timeout=600)
        if result.returncode != 0:
            raise RuntimeError("sim_batch failed: " + result.stderr)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_plots_and_csv_hold_the_logs_values(self):
        out = os.path.join(self.dir, "plots")
        os.mkdir(out)
        result = run_script(self.run_path, "--out", out, "--csv")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stderr, "")
        for name in PICTURES:
            check_picture(self, os.path.join(out, "tongue_%s.png" % name))

        with h5py.File(self.run_path, "r") as f:
            time = f["/time"][()]
            positions = f["/positions"][()]
            sets = {name: f["/mesh/node_sets/" + name][()] for name in f["/mesh/node_sets"]}
            names = [n.decode() if isinstance(n, bytes) else n for n in f["/muscles/names"][()]]
            activations = f["/activations"][()]
            max_force = f["/muscles/max_force"][()]
        self.assertEqual(len(time), 7)

        landmarks = read_csv(os.path.join(out, "tongue_landmarks.csv"))
        expected = ["time_ms"] + [landmark + axis for landmark in
                                  ("tip", "palatal_dorsum", "velar_dorsum", "root")
                                  for axis in ("_x_mm", "_y_mm")]
        self.assertEqual(list(landmarks), expected)
        np.testing.assert_array_equal(landmarks["time_ms"], time * 1e3)
        for landmark in ("tip", "palatal_dorsum", "velar_dorsum", "root"):
            node = sets[landmark][0]
            for axis, component in (("_x_mm", 0), ("_y_mm", 1)):
                np.testing.assert_array_equal(landmarks[landmark + axis],
                                              positions[:, node, component] * 1e3)
        # The landmarks moved (gravity and the muscle), so the trajectories are not flat.
        self.assertGreater(np.ptp(landmarks["tip_y_mm"]), 1e-3)

        muscles = read_csv(os.path.join(out, "tongue_muscles.csv"))
        ever = [i for i in range(len(names)) if activations[:, i].max() > 0]
        self.assertEqual([names[i] for i in ever], ["SG_left", "SG_right"])
        self.assertEqual(list(muscles), ["time_ms"] + [names[i] + suffix for i in ever
                                                       for suffix in ("_activation", "_force_N")])
        for i in ever:
            np.testing.assert_array_equal(muscles[names[i] + "_activation"], activations[:, i])
            np.testing.assert_array_equal(muscles[names[i] + "_force_N"],
                                          activations[:, i] * max_force[i])
        # 3 N over both halves while on; sim_batch's step to t uses the levels at t, so the steps
        # to 4, 8 and 12 ms. Within round-off of 3 N = (3 / 24) x 24 N.
        total = muscles["SG_left_force_N"] + muscles["SG_right_force_N"]
        np.testing.assert_allclose(total, [0, 3, 3, 3, 0, 0, 0], rtol=0, atol=1e-12)

    def test_times_pick_the_nearest_frames(self):
        out = os.path.join(self.dir, "times")
        os.mkdir(out)
        result = run_script(self.run_path, "--out", out, "--times", "0", "0.011", "0.024")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("frames 0, 3, 6 (t = 0.0, 12.0, 24.0 ms)", result.stdout)
        check_picture(self, os.path.join(out, "tongue_shapes.png"))
        self.assertFalse(os.path.exists(os.path.join(out, "tongue_landmarks.csv")))  # no --csv

    def test_default_shapes_are_first_last_and_evenly_spaced(self):
        out = os.path.join(self.dir, "default")
        os.mkdir(out)
        result = run_script(self.run_path, "--out", out)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("frames 0, 2, 3, 4, 6 ", result.stdout)


class SyntheticRuns(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="plot_run_")
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def test_all_three_plots_of_a_box_by_default_beside_the_run(self):
        run = self.path("box.h5")
        write_box_run(run)
        result = run_script(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        for name in PICTURES:
            check_picture(self, self.path("box_%s.png" % name))
        self.assertIn("landmarks tip (node", result.stdout)
        self.assertIn("muscles a", result.stdout)

    def test_plots_without_data_are_skipped_with_a_reason(self):
        run = self.path("bare.h5")
        write_box_run(run, landmarks=False, muscles=False)
        result = run_script(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("skipped the landmark trajectories: no landmark node set", result.stderr)
        self.assertIn("skipped the muscles: no muscles in the run file", result.stderr)
        self.assertFalse(os.path.exists(self.path("bare_landmarks.png")))
        self.assertFalse(os.path.exists(self.path("bare_muscles.png")))
        check_picture(self, self.path("bare_shapes.png"))

        run = self.path("idle.h5")
        write_box_run(run, active=False)
        result = run_script(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("skipped the muscles: no muscle was ever active", result.stderr)

        run = self.path("lateral.h5")  # no midsagittal set, nothing crosses z = 0
        write_box_run(run, crossing=False)
        result = run_script(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("skipped the midsagittal shapes: no midsagittal section", result.stderr)
        check_picture(self, self.path("lateral_landmarks.png"))

    def test_a_log_with_nothing_to_plot_fails(self):
        run = self.path("nothing.h5")
        write_box_run(run, landmarks=False, muscles=False, crossing=False)
        result = run_script(run)
        self.assertEqual(result.returncode, 1)
        self.assertIn("nothing to plot", result.stderr)

    def test_errors_name_the_problem(self):
        result = run_script(self.path("nowhere.h5"))
        self.assertEqual(result.returncode, 1)
        self.assertIn("no such run file", result.stderr)
        self.assertIn("nowhere.h5", result.stderr)

        run = self.path("box.h5")
        write_box_run(run)
        result = run_script(run, "--times", "0.5")
        self.assertEqual(result.returncode, 1)
        self.assertIn("--times 0.5 s is outside the run (0 s to 0.004 s)", result.stderr)
        self.assertFalse(os.path.exists(self.path("box_shapes.png")))

        result = run_script(run, "--out", self.path("missing_dir"))
        self.assertEqual(result.returncode, 1)
        self.assertIn("no such directory", result.stderr)

        broken = self.path("broken.h5")
        with h5py.File(broken, "w") as f:
            f["/time"] = np.zeros(2)
        result = run_script(broken)
        self.assertEqual(result.returncode, 1)
        self.assertIn("/rest_positions", result.stderr)

        result = run_script(run, "--times")
        self.assertEqual(result.returncode, 2)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: test_plot_run.py PATH/TO/plot_run.py PATH/TO/sim_batch")
    SCRIPT = os.path.abspath(sys.argv.pop(1))
    SIM_BATCH = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
