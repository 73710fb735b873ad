"""The Python module `tongue` (python/): Simulation against sim_batch, run by CTest with the
module's build folder on PYTHONPATH and SIM_BATCH naming the sim_batch program."""
import os
import subprocess
import warnings

import h5py
import numpy as np
import pytest

import tongue

PROJECT = os.environ["PROJECT_DIR"]
SG_3N = os.path.join(PROJECT, "scenes", "tongue_sg_3n.yaml")


def sg_levels(sim, force_n):
    """The scene's own activation: force_n over SG_left and SG_right, split by F_max (the same
    level for both), as the scene file's `{group: SG, force: 3.0}` does."""
    sg = [i for i, name in enumerate(sim.muscle_names) if name.startswith("SG_")]
    levels = np.zeros(len(sim.muscle_names))
    levels[sg] = force_n / sim.max_forces[sg].sum()
    return levels


@pytest.fixture(scope="module")
def sim():
    return tongue.Simulation(SG_3N)


def test_steps_the_scene_as_sim_batch_does_bit_for_bit(sim, tmp_path):
    # sim_batch runs the scene's schedule (SG 3 N for its 30 steps of 4 ms); the module gets the
    # same levels step by step: the same run object, so the same states to the last bit.
    run_file = tmp_path / "batch.h5"
    subprocess.run([os.environ["SIM_BATCH"], SG_3N, "--quiet", "--output", str(run_file)],
                   check=True, capture_output=True)
    sim.reset()
    levels = sg_levels(sim, 3.0)
    with h5py.File(run_file, "r") as f:
        positions, times = f["positions"][:], f["time"][:]
    assert np.array_equal(sim.positions, positions[0])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for k in range(1, len(times)):
            figures = sim.step(levels)
            assert figures.time == times[k]
            assert np.array_equal(sim.positions, positions[k]), f"step {k}"
    assert sim.step_count == len(times) - 1
    # The paper's law loses strong ellipticity in this run (as sim_batch warns): said, not lost.
    assert any("strongly elliptic" in str(w.message) for w in caught)


def test_a_reset_run_warns_again_at_the_same_step(sim):
    # SG 3 N strains the paper's law beyond strong ellipticity within its 30 steps: every run
    # after a reset says so again, at the same state, and finish_checks() takes what the last
    # state's check found.
    def run():
        sim.reset()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            said = [w for _ in range(30) for w in sim.step(sg_levels(sim, 3.0)).warnings]
            return said + sim.finish_checks()
    first = run()
    assert len(first) == 1 and "strongly elliptic" in first[0]
    assert run() == first


def test_named_levels_set_groups_and_keep_the_rest(sim):
    sim.reset()
    sim.step({"SG": 0.1, "GGp_left": 0.2})
    names = sim.muscle_names
    assert sim.levels[names.index("SG_left")] == 0.1
    assert sim.levels[names.index("SG_right")] == 0.1
    assert sim.levels[names.index("GGp_left")] == 0.2
    sim.step({"GGp_left": 0.0})
    assert sim.levels[names.index("SG_right")] == 0.1  # kept
    assert sim.levels[names.index("GGp_left")] == 0.0


def test_reset_repeats_the_run(sim):
    levels = sg_levels(sim, 2.0)
    sim.reset()
    rest = sim.positions.copy()
    for _ in range(5):
        sim.step(levels)
    first = sim.positions.copy()
    assert not np.array_equal(first, rest)
    sim.reset()
    assert sim.time == 0.0 and sim.step_count == 0
    assert np.array_equal(sim.positions, rest)
    for _ in range(5):
        sim.step(levels)
    assert np.array_equal(sim.positions, first)


def test_a_reset_told_the_first_levels_saves_the_first_steps_factorization(sim):
    # The first step's factor is formed at the reset under the levels given, as sim_batch forms
    # it at start-up: the first step then forms none, and the states are the same to the bit.
    levels = sg_levels(sim, 2.0)
    sim.reset()
    first = sim.step(levels)
    assert first.factorizations == 1  # SG 2 N is far from the muscles-off factor's levels
    runs = []
    for first_levels in (levels, {"SG": levels[sim.muscle_names.index("SG_left")]}):
        sim.reset(first_levels)
        figures = [sim.step(levels) for _ in range(5)]
        assert figures[0].factorizations == 0
        runs.append(sim.positions.copy())
    sim.reset()
    for _ in range(5):
        sim.step(levels)
    assert np.array_equal(runs[0], sim.positions)
    assert np.array_equal(runs[1], sim.positions)
    with pytest.raises(ValueError, match="first levels for"):
        sim.reset(np.zeros(3))
    with pytest.raises(ValueError, match="outside"):
        sim.reset({"SG": 1.5})
    with pytest.raises(ValueError, match="neither a muscle nor a group"):
        sim.reset({"XX": 0.1})


def test_the_model_and_the_state_in_si_units(sim):
    sim.reset()
    n = sim.rest_positions.shape[0]
    assert sim.positions.shape == (n, 3) and sim.velocities.shape == (n, 3)
    assert sim.elements.shape[1] == 8 and sim.elements.max() == n - 1
    assert sim.dt == pytest.approx(0.004)
    assert len(sim.max_forces) == len(sim.muscle_names) == len(sim.muscle_lengths)
    # The built-in tongue is about 6 cm long and its muscles' lengths are centimetres.
    extent = sim.rest_positions.max(axis=0) - sim.rest_positions.min(axis=0)
    assert 0.03 < extent.max() < 0.1
    assert 0.005 < np.median(sim.muscle_lengths) < 0.1
    # positions = rest + displacement, so subtracting again is exact to one rounding of
    # coordinates below 0.1 m (an ulp of 1.4e-17 m).
    assert np.allclose(sim.displacements, sim.positions - sim.rest_positions, rtol=0, atol=1e-16)
    assert "tip" in sim.node_sets


def test_bad_input_raises_with_the_library_s_message(sim):
    with pytest.raises(ValueError, match="activation levels for 19 muscles"):
        sim.step(np.zeros(3))
    with pytest.raises(ValueError, match="out of range|outside"):
        sim.step(np.full(len(sim.muscle_names), 1.5))
    with pytest.raises(ValueError, match="'XX' is neither a muscle nor a group"):
        sim.step({"XX": 0.1})
    with pytest.raises(RuntimeError, match="missing.yaml"):
        tongue.Simulation(os.path.join(PROJECT, "missing.yaml"))


def test_run_file_holds_what_sim_batch_writes(sim, tmp_path):
    batch = tmp_path / "batch.h5"
    subprocess.run([os.environ["SIM_BATCH"], SG_3N, "--quiet", "--output", str(batch)],
                   check=True, capture_output=True)
    sim.reset()
    sim.run_file(str(tmp_path / "python.h5"))
    assert sim.run_file_path == str(tmp_path / "python.h5")
    levels = sg_levels(sim, 3.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the material's, tested above
        for _ in range(30):
            sim.step(levels)
    sim.reset()  # logged as a frame at t = 0 and counted
    sim.close_run_file()
    run, reference = tongue.RunFile(str(tmp_path / "python.h5")), tongue.RunFile(str(batch))
    assert run.status == "completed"
    for name in ["/positions", "/time", "/activations", "/muscles/length", "/muscles/velocity"]:
        assert np.array_equal(run.dataset(name)[:31], reference.dataset(name)), name
    assert run.time[31] == 0.0 and np.array_equal(run.positions[31], run.positions[0])
    assert np.array_equal(run.rest_positions, reference.rest_positions)
    assert run.dataset("/solver/iterations")[1:31].min() >= 1
    with h5py.File(tmp_path / "python.h5", "r") as f:
        assert f.attrs["resets"] in ("1", b"1")


def test_a_run_file_that_cannot_be_created_is_named(sim, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(RuntimeError, match=str(blocker)):
        sim.run_file(str(blocker / "run.h5"))
