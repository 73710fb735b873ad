"""The controllers written in Python (controllers/python) against their C++ counterparts: each
drives a real sim_server on its own loopback port, and the two run files are equal to the last
bit (the same arithmetic in the same order on the same doubles)."""
import os
import signal
import subprocess
import time

import h5py
import numpy as np

from server_process import PROCESS_TIMEOUT_S, path, run_controller, url

FIELDS = ["positions", "activations", "muscles/length", "muscles/velocity", "time"]


def same_runs(a, b):
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        for name in FIELDS:
            assert np.array_equal(fa[name][:], fb[name][:]), name
        return fa["positions"].shape[0]


def test_step_controller_reproduces_sequence_player(tmp_path):
    # SG 3 N for 120 ms, then 200 ms of relaxation: the schedule's duration ends both players.
    schedule = path("controllers", "sequences", "sg_3n_relax.yaml")
    code, err, _ = run_controller(7856, "tongue_sg_3n_relax.yaml", tmp_path / "cpp.h5",
                                  [os.environ["SEQUENCE_PLAYER"], "--schedule", schedule], ["--max-steps", "80"])
    assert code == 0, err
    code, err, _ = run_controller(7857, "tongue_sg_3n_relax.yaml", tmp_path / "py.h5",
                                  [os.environ["PY_STEP_CONTROLLER"], "--schedule", schedule], ["--max-steps", "80"])
    assert code == 0, err
    assert "reached step 80 (the controller's last step)" in err
    assert same_runs(tmp_path / "cpp.h5", tmp_path / "py.h5") == 81


def test_ep_controller_reproduces_the_cpp_one(tmp_path):
    # The /ai/ plan in closed loop (the main job's controller and scene), 40 steps of 8 ms: into
    # the /i/ transition, where the delay's interpolation and the force lag both act.
    plan = path("controllers", "plans", "ai.yaml")
    args = ["--plan", plan, "--max-steps", "40"]
    code, err, _ = run_controller(7858, "tongue_ep.yaml", tmp_path / "cpp.h5",
                                  [os.environ["EP_CONTROLLER"], *args], ["--max-steps", "40"])
    assert code == 0, err
    code, err, _ = run_controller(7859, "tongue_ep.yaml", tmp_path / "py.h5",
                                  [os.environ["PY_EP_CONTROLLER"], *args], ["--max-steps", "40"])
    assert code == 0, err
    assert "delay 1.5 steps (12 ms at dt 8 ms)" in err
    assert same_runs(tmp_path / "cpp.h5", tmp_path / "py.h5") == 41
    with h5py.File(tmp_path / "py.h5", "r") as f:
        assert f["activations"][:].max() > 0.0  # the loop did drive the tongue


def test_bad_input_exits_1_with_the_file_and_key(tmp_path):
    plan = tmp_path / "plan.yaml"
    plan.write_text("delta_lambda_mm:\n  GGa: [-10, oops]\n")
    done = subprocess.run([os.environ["PY_EP_CONTROLLER"], "--plan", str(plan)],
                          capture_output=True, text=True, timeout=PROCESS_TIMEOUT_S)
    assert done.returncode == 1
    assert f"{plan}: delta_lambda_mm.GGa[1]: expected a finite number" in done.stderr
    done = subprocess.run([os.environ["PY_STEP_CONTROLLER"], "--frobnicate", "1"],
                          capture_output=True, text=True, timeout=PROCESS_TIMEOUT_S)
    assert done.returncode == 1
    assert "usage: step_controller.py" in done.stderr
    done = subprocess.run([os.environ["PY_STEP_CONTROLLER"], "--schedule", "/nonexistent.yaml"],
                          capture_output=True, text=True, timeout=PROCESS_TIMEOUT_S)
    assert done.returncode == 1 and "/nonexistent.yaml: cannot be read" in done.stderr


def test_a_silent_bus_times_out_with_exit_4():
    done = subprocess.run([os.environ["PY_STEP_CONTROLLER"], "--schedule",
                           path("controllers", "sequences", "sg_3n.yaml"), "--lcm-url",
                           url(7860), "--timeout-s", "0.5"],
                          capture_output=True, text=True, timeout=PROCESS_TIMEOUT_S)
    assert done.returncode == 4, done.stderr
    assert "no model on TONGUE_MODEL" in done.stderr


def wait_for_receiver(port):
    """Until a socket listens on udp port: the controller's bus is open, its handlers are set."""
    deadline = time.monotonic() + PROCESS_TIMEOUT_S
    while time.monotonic() < deadline:
        with open("/proc/net/udp", encoding="ascii") as table:
            if any(line.split()[1].endswith(f":{port:04X}") for line in list(table)[1:]):
                return
        time.sleep(0.05)
    raise TimeoutError(f"nothing listens on udp port {port}")


def test_sigint_and_sigterm_end_it_with_exit_130_and_its_summary():
    for sig, port in ((signal.SIGINT, 7861), (signal.SIGTERM, 7862)):
        controller = subprocess.Popen(
            [os.environ["PY_STEP_CONTROLLER"], "--schedule",
             path("controllers", "sequences", "sg_3n.yaml"), "--lcm-url", url(port),
             "--timeout-s", "600"], stderr=subprocess.PIPE, text=True)
        try:
            wait_for_receiver(port)  # in its wait for a model that never comes
            controller.send_signal(sig)
            _, err = controller.communicate(timeout=PROCESS_TIMEOUT_S)
        finally:
            controller.kill()
        assert controller.returncode == 130, err
        assert "step_controller.py: stopped by KeyboardInterrupt;" in err
