#!/usr/bin/python3
"""Test of scripts/epg.py on synthetic run files.

usage: test_epg.py PATH/TO/epg.py

A flat palate 40 mm long (x from 20 to -20 mm) and 30 mm wide (z from -15 to 15 mm) at y = 50 mm,
crossing z = 0, and nodes pressed on it at known places: each must switch on the electrode of
the Reading grid whose cell holds it, and nothing else.
Run with Debian's Python (python3-h5py, python3-numpy, python3-matplotlib).
"""
import os
import subprocess
import sys
import tempfile
import unittest

import h5py
import numpy as np

SCRIPT = None
ROW_SIZES = [6] + [8] * 7


def palate(nx=16, nz=12):
    xs = np.linspace(0.02, -0.02, nx + 1)  # front (x = 20 mm) to back
    zs = np.linspace(-0.015, 0.015, nz + 1)
    vertices = np.array([(x, 0.05, z) for x in xs for z in zs])
    triangles = []
    for i in range(nx):
        for j in range(nz):
            a, b = i * (nz + 1) + j, (i + 1) * (nz + 1) + j
            triangles += [[a, b, b + 1], [a, b + 1, a + 1]]
    return vertices, np.array(triangles, np.int32)


def write_run(path, contacts):
    """contacts: per frame, a list of (x, z) [m] where a node touches the palate."""
    v, t = palate()
    nodes = max(len(c) for c in contacts) + 2
    positions = np.zeros((len(contacts), nodes, 3))
    forces = np.zeros((len(contacts), nodes, 3))
    for k, frame in enumerate(contacts):
        positions[k, :, 1] = 0.03  # nodes off the palate, unpushed
        for n, (x, z) in enumerate(frame):
            positions[k, n] = (x, 0.04999, z)
            forces[k, n] = (0.0, -0.01, 0.0)
    with h5py.File(path, "w") as f:
        f.create_dataset("/time", data=0.004 * np.arange(len(contacts)))
        f.create_dataset("/positions", data=positions)
        f.create_dataset("/obstacles/names",
                         data=np.array(["hard_palate", "velum"], dtype=h5py.string_dtype()))
        f.create_dataset("/obstacles/hard_palate/vertices", data=v)
        f.create_dataset("/obstacles/hard_palate/triangles", data=t)
        f.create_dataset("/obstacles/velum/vertices", data=v)
        f.create_dataset("/obstacles/velum/triangles", data=t)
        f.create_dataset("/contact/node_force", data=forces)


def electrode(row, col):
    return sum(ROW_SIZES[:row]) + col


def run_script(*args):
    return subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True,
                          timeout=120)


class EpgTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="epg_")
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_contacts_switch_on_the_electrodes_of_their_cells(self):
        run = os.path.join(self.dir, "run.h5")
        # Frame 0: nothing. Frame 1: the front row's rightmost cell (z near -15 mm at the front
        # edge), the middle of row 4 on the left half, the back row's leftmost cell.
        write_run(run, [[], [(0.0195, -0.0145), (-0.0005, 0.001), (-0.0195, 0.0145)]])
        csv = os.path.join(self.dir, "epg.csv")
        png = os.path.join(self.dir, "epg.png")
        result = run_script(run, "-o", png, "--csv", csv, "--frames", "0", "1")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(os.path.isfile(png))
        table = np.loadtxt(csv, delimiter=",", skiprows=1)
        self.assertEqual(table.shape, (2, 63))
        self.assertEqual(table[0, 1:].sum(), 0)
        on = set(np.flatnonzero(table[1, 1:]))
        # x = -0.5 mm is 20.5 / 40 of the way back: row 5 (index 4); z = +1 mm: just left of
        # the middle of 8 columns (index 4).
        self.assertEqual(on, {electrode(0, 0), electrode(4, 4), electrode(7, 7)})
        self.assertIn("3 of 62", result.stdout)

    def test_a_run_without_contact_or_palate_fails_with_a_message(self):
        run = os.path.join(self.dir, "bare.h5")
        with h5py.File(run, "w") as f:
            f.create_dataset("/time", data=[0.0])
        result = run_script(run)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("no obstacles", result.stderr)
        run = os.path.join(self.dir, "run.h5")
        write_run(run, [[]])
        result = run_script(run, "--palate", "roof")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("no obstacle 'roof'", result.stderr)
        result = run_script(os.path.join(self.dir, "nowhere.h5"))
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("nowhere.h5", result.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: test_epg.py PATH/TO/epg.py")
    SCRIPT = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
