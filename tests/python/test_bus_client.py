"""tongue.BusClient against a real sim_server on its own loopback udpm port per test."""
import h5py
import numpy as np
import pytest

import tongue
from server_process import Server, url


def client(port, **options):
    return tongue.BusClient(tongue.ControllerOptions(lcm_url=url(port), **options),
                            program="bus_client_test")


def test_lockstep_run_with_named_levels(tmp_path):
    c = client(7863, max_steps=10)  # receiving before the server starts: nothing is missed
    server = Server(7863, "tongue_sg_3n.yaml", tmp_path / "run.h5", "--max-steps", "10")
    try:
        model = c.connect()
        assert model is not None and model.dt == pytest.approx(0.004)
        assert model.rest_positions.shape == (model.num_nodes, 3)
        assert model.elements.shape[1] == 8
        assert "tip" in model.landmarks and "SG_left" in model.muscle_names
        steps = []
        for state in c.lockstep():
            steps.append(state.step)
            assert state.converged and state.positions.shape == (len(state.node_indices), 3)
            c.send({"SG": 0.125, "GGp_left": 0.05})  # a group and a muscle
        assert server.wait()[0] == 0
    finally:
        server.kill()
    assert steps == list(range(11))
    assert (c.exit_code, c.reason) == (0, "reached step 10 (--max-steps)")
    assert "11 states received (steps 0-10), 10 activations sent (lockstep)" in c.summary()
    with h5py.File(tmp_path / "run.h5", "r") as f:
        names = [n.decode() if isinstance(n, bytes) else n for n in f["muscles/names"][:]]
        levels = f["activations"][-1]
    assert levels[names.index("SG_right")] == 0.125
    assert levels[names.index("GGp_left")] == 0.05
    assert levels[names.index("GGp_right")] == 0.0


def test_misuse_is_raised_and_bus_trouble_ends_with_the_controllers_exit_codes(tmp_path):
    c = client(7864, max_steps=3)
    server = Server(7864, "tongue_sg_3n.yaml", tmp_path / "run.h5")
    try:
        c.connect()
        state = next(iter(c))
        assert state.step == 0 and c.awaiting_answer
        with pytest.raises(ValueError, match="'XY' is no muscle or group"):
            c.send({"XY": 0.1})
        with pytest.raises(ValueError, match="3 values for 19 muscles"):
            c.send([0.0, 0.1, 0.2])
        with pytest.raises(RuntimeError, match="not answered yet"):
            next(iter(c))
        c.send(np.zeros(19))
        with pytest.raises(RuntimeError, match="answered already"):
            c.send(np.zeros(19))
        with pytest.raises(ValueError, match="lockstep mode, not realtime"):
            c.realtime()
        # A level the server refuses: its rejection notice ends the session with exit 5.
        assert next(iter(c)).step == 1
        c.send({"SG": 1.5})
        assert list(c) == []
        assert c.exit_code == 5 and "rejected its activation for step 2" in c.reason
    finally:
        server.kill()


def test_realtime_mode(tmp_path):
    c = client(7865, mode="realtime", max_steps=15)
    server = Server(7865, "tongue_sg_3n.yaml", tmp_path / "run.h5", "--mode", "realtime",
                    "--max-steps", "15")
    try:
        assert c.connect() is not None
        seen = [state.step for state in c.realtime() if c.send({"SG": 0.125}) is None]
        assert server.wait()[0] == 0
    finally:
        server.kill()
    assert c.exit_code == 0 and seen[-1] == 15 and seen == sorted(seen)
    assert "activations sent (realtime)" in c.summary()


def test_no_server_times_out_with_exit_4():
    c = client(7866, timeout_s=0.3)
    assert c.connect() is None
    assert c.exit_code == 4 and c.reason.startswith("no model on TONGUE_MODEL")
    assert list(c) == []


def test_options_are_checked_as_the_command_line_is():
    with pytest.raises(tongue.UsageError, match="--mode must be lockstep or realtime"):
        tongue.ControllerOptions(mode="fast")
    with pytest.raises(ValueError, match="--prefix"):
        tongue.ControllerOptions(prefix="lower_")
    options, values, wants_help = tongue.parse_controller_command_line(
        ["--plan", "p.yaml", "--max-steps", "7"], ["--plan"])
    assert (options.max_steps, values, wants_help) == (7, {"--plan": "p.yaml"}, False)
    assert tongue.select_muscles("SG", ["SG_left", "SGX", "SG_right"]) == [0, 2]
