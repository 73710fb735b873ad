"""The Python module's RunFile against the same run file read with h5py."""
import os
import subprocess

import h5py
import numpy as np
import pytest

import tongue

PROJECT = os.environ["PROJECT_DIR"]


@pytest.fixture(scope="module")
def run_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("run") / "sg3n.h5"
    scene = os.path.join(PROJECT, "scenes", "tongue_sg_3n.yaml")
    subprocess.run([os.environ["SIM_BATCH"], scene, "--quiet", "--output", str(path)],
                   check=True, capture_output=True)
    return path


def test_arrays_are_the_file_s(run_path):
    run = tongue.RunFile(str(run_path))
    with h5py.File(run_path, "r") as f:
        assert np.array_equal(run.time, f["time"][:])
        assert np.array_equal(run.positions, f["positions"][:])
        assert np.array_equal(run.rest_positions, f["rest_positions"][:])
        assert np.array_equal(run.activations, f["activations"][:])
        assert np.array_equal(run.dataset("/solver/iterations"), f["solver/iterations"][:])
        names = [n.decode() if isinstance(n, bytes) else n for n in f["muscles/names"][:]]
        assert run.muscle_names == names
        sg = names.index("SG_left")
        series = run.muscle("SG_left")
        assert np.array_equal(series["activation"], f["activations"][:, sg])
        assert np.array_equal(series["length"], f["muscles/length"][:, sg])
        assert np.array_equal(series["velocity"], f["muscles/velocity"][:, sg])
    assert run.status == "completed"
    assert run.has("/muscles") and not run.has("/contact")
    # SG pulls from the first step on: its level is 3 N over the two SG muscles' F_max.
    assert series["activation"][0] == 0.0 and series["activation"][1] > 0.0


def test_bad_names_and_files_raise(run_path, tmp_path):
    run = tongue.RunFile(str(run_path))
    with pytest.raises(ValueError, match="no muscle 'XX'"):
        run.muscle("XX")
    with pytest.raises(RuntimeError, match="/nothing"):
        run.dataset("/nothing")
    not_hdf5 = tmp_path / "text.h5"
    not_hdf5.write_text("not a run file")
    with pytest.raises(RuntimeError, match="cannot open as an HDF5 run file"):
        tongue.RunFile(str(not_hdf5))
