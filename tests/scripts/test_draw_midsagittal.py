#!/usr/bin/python3
"""Integration test of scripts/draw_midsagittal.py on small synthetic run files.

usage: test_draw_midsagittal.py PATH/TO/draw_midsagittal.py

Writes run files with h5py in a temporary folder, as sim_batch lays them out: a 2 x 2 x 2 box of
hex8 (10 x 10 x 10 mm) straddling z = 0, its middle node layer the "midsagittal" node set, a muscle
"SG_left"/"SG_right" pair and an "SL" element set, landmarks, 2 frames (rest, then the top
pulled back and up). Runs the script and checks the pictures and the error handling.
Run with Debian's Python (python3-h5py, python3-numpy, python3-matplotlib).
"""
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
WIDTH, HEIGHT = 800, 640  # the section picture: 8 x 6.4 in at 100 dpi


def box_mesh(n=2, size=0.01):
    """Nodes (i, j, k) -> i + (n+1) (j + (n+1) k); z from -size/2 to size/2."""
    h = size / n
    nodes = []
    for k in range(n + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                nodes.append((i * h, j * h, k * h - size / 2))
    idx = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)  # noqa: E731
    elements = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                elements.append([idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k),
                                 idx(i, j + 1, k), idx(i, j, k + 1), idx(i + 1, j, k + 1),
                                 idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)])
    return np.array(nodes), np.array(elements, dtype=np.int32), idx


def write_run(path, midsagittal=True, drop=None, muscles=True, obstacle=False):
    rest, elements, idx = box_mesh()
    final = rest.copy()
    # Deform: the top (y = 10 mm) moves back by 2 mm and up by 1.5 mm, scaled by the height.
    final[:, 0] -= 0.2 * rest[:, 1]
    final[:, 1] += 0.15 * rest[:, 1]
    positions = np.stack([rest, final])
    with h5py.File(path, "w") as f:
        data = {"/rest_positions": rest, "/elements": elements,
                "/time": np.array([0.0, 0.12]), "/positions": positions}
        for name, value in data.items():
            if name != drop:
                f.create_dataset(name, data=value)
        mid = [n for n in range(len(rest)) if abs(rest[n, 2]) < 1e-12]
        if midsagittal:
            f.create_dataset("/mesh/node_sets/midsagittal", data=np.array(mid, np.int32))
        f.create_dataset("/mesh/node_sets/tip", data=np.array([idx(2, 2, 1)], np.int32))
        f.create_dataset("/mesh/node_sets/root", data=np.array([idx(0, 2, 1)], np.int32))
        f.create_dataset("/mesh/node_sets/gg_insertion", data=np.array([idx(1, 0, 1)], np.int32))
        f.create_dataset("/mesh/element_sets/all", data=np.arange(len(elements), dtype=np.int32))
        # Elements (i, j, k) = i + 2 (j + 2 k): SG the back column, SL the top front ones.
        f.create_dataset("/mesh/element_sets/SG_left", data=np.array([4], np.int32))
        f.create_dataset("/mesh/element_sets/SG_right", data=np.array([0], np.int32))
        f.create_dataset("/mesh/element_sets/SL", data=np.array([3, 7], np.int32))
        if muscles:
            names = ["SG_left", "SG_right", "SL"]
            f.create_dataset("/muscles/names", data=np.array(names, dtype=h5py.string_dtype()))
            f.create_dataset("/muscles/max_force", data=np.array([1.5, 1.5, 1.0]))
            f.create_dataset("/activations", data=np.array([[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]]))
        if obstacle:
            # A roof at y = 12 mm over the box, across z = 0 (its section a line from x = -5 to
            # 15 mm); the top midsagittal nodes pressed on it in frame 1.
            v = np.array([[-0.005, 0.012, -0.01], [0.015, 0.012, -0.01], [0.015, 0.012, 0.01],
                          [-0.005, 0.012, 0.01]])
            f.create_dataset("/obstacles/names", data=np.array(["roof"], dtype=h5py.string_dtype()))
            f.create_dataset("/obstacles/roof/vertices", data=v)
            f.create_dataset("/obstacles/roof/triangles",
                             data=np.array([[0, 2, 1], [0, 3, 2]], np.int32))
            force = np.zeros((2, len(rest), 3))
            for i in range(3):
                force[1, idx(i, 2, 1), 1] = -0.1
            f.create_dataset("/contact/node_force", data=force)


def run_script(*args):
    return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True,
                          timeout=120)


def dark_fraction(png, level=0.45):
    image = mpimg.imread(png)
    rgb = image[..., :3]
    return image.shape, float(np.mean(rgb.mean(axis=-1) < level))


class DrawMidsagittalTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="draw_midsagittal_")
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def test_draws_the_section_with_the_default_output_name(self):
        run = self.path("box_run.h5")
        write_run(run)
        result = run_script(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        png = self.path("box_run_midsagittal.png")
        self.assertTrue(os.path.isfile(png), result.stdout)
        shape, dark = dark_fraction(png)
        self.assertEqual(shape[:2], (HEIGHT, WIDTH))
        self.assertGreater(dark, 0.005, "the picture has (almost) no dark pixels")
        image = mpimg.imread(png)[..., :3]
        self.assertGreater(float(np.std(image)), 0.05, "the picture is blank")
        grey = image.mean(axis=-1)
        # The muscle's face (#5a5a5a) covers a quarter of the section; the rest is light grey.
        self.assertGreater(float(np.mean(np.abs(grey - 0x5a / 255) < 0.02)), 0.01,
                           "no dark-grey muscle face")
        self.assertGreater(float(np.mean(np.abs(grey - 0xd9 / 255) < 0.02)), 0.03,
                           "no light-grey rest section")
        self.assertIn("SG_left", result.stdout)
        self.assertIn("SG_right", result.stdout)

    def test_explicit_output_frame_muscle_group_and_3d_view(self):
        run = self.path("box_run.h5")
        write_run(run)
        out = self.path("section.png")
        out3d = self.path("view3d.png")
        result = run_script(run, "-o", out, "--frame", "1", "--muscle", "SL",
                            "--view3d", out3d)
        self.assertEqual(result.returncode, 0, result.stderr)
        for png in (out, out3d):
            self.assertTrue(os.path.isfile(png), png)
            _, dark = dark_fraction(png)
            self.assertGreater(dark, 0.001, png)
        self.assertIn("SL", result.stdout)
        self.assertNotIn("SG_left", result.stdout)
        result = run_script(run, "-o", out, "--muscle", "SG")  # the group: both halves
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("SG_left, SG_right", result.stdout)

    def test_without_midsagittal_set_falls_back_to_elements_crossing_z0(self):
        run = self.path("no_mid.h5")
        write_run(run, midsagittal=False, muscles=False)
        out = self.path("no_mid.png")
        result = run_script(run, "-o", out, "--frame", "0")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("crossing z = 0", result.stdout)
        self.assertTrue(os.path.isfile(out))

    def test_obstacles_and_contact_nodes_are_drawn(self):
        run = self.path("roof.h5")
        write_run(run, obstacle=True)
        out = self.path("roof.png")
        result = run_script(run, "-o", out, "--frame", "1")
        self.assertEqual(result.returncode, 0, result.stderr)
        image = mpimg.imread(out)[..., :3]
        # The obstacle's line (#1b6f3a) and the contact marks (#e67e22) are there.
        for colour, what in ((0x1b6f3a, "obstacle line"), (0xe67e22, "contact marks")):
            rgb = np.array([(colour >> 16) & 255, (colour >> 8) & 255, colour & 255]) / 255.0
            self.assertGreater(float(np.mean(np.abs(image - rgb).max(axis=-1) < 0.05)), 1e-4,
                               what)

    def test_missing_dataset_is_named_and_fails(self):
        for dataset in ("/positions", "/elements", "/rest_positions", "/time"):
            run = self.path("broken.h5")
            write_run(run, drop=dataset)
            out = self.path("broken.png")
            result = run_script(run, "-o", out)
            self.assertNotEqual(result.returncode, 0, dataset)
            self.assertIn(dataset, result.stderr)
            self.assertFalse(os.path.exists(out), dataset)

    def test_missing_file_unknown_muscle_and_bad_frame_fail(self):
        result = run_script(self.path("nowhere.h5"))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("nowhere.h5", result.stderr)
        run = self.path("box_run.h5")
        write_run(run)
        result = run_script(run, "--muscle", "XYZ")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("XYZ", result.stderr)
        result = run_script(run, "--frame", "7")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("frame", result.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: test_draw_midsagittal.py PATH/TO/draw_midsagittal.py")
    SCRIPT = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
