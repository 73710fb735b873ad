"""Sweeps on a local cluster of two workers against the same runs in-process, one after the
other; resume after a crash; failures in their rows. No timing is asserted."""
import json
import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

import tongue
from conftest import PROJECT, SG_3N, repeatable
from tongue_sweep import Sweep, make_runs

LEVELS = [{"levels.SG": 0.05}, {"levels.SG": 0.1}, {"levels.SG": 0.125},
          {"levels.GGp": 0.1}, {"levels.SG": 0.1, "levels.GGp": 0.05},
          {"levels.SG": 0.125, "release_s": 0.012}]


def small_runs(steps=8):
    return make_runs([{"scene": SG_3N, "steps": steps, **levels} for levels in LEVELS])


class Crash(Exception):
    pass


def test_a_sweep_gives_the_figures_of_the_runs_done_in_process(client, tmp_path):
    runs = small_runs()
    rows = Sweep(tmp_path / "cluster", client).run(runs)
    assert [r["status"] for r in rows] == ["ok"] * len(runs)
    assert len({r["worker"] for r in rows}) >= 1
    # The same runs here, one after the other, through the module directly.
    sim = tongue.Simulation(SG_3N)
    tip = sim.node_sets["tip"][0]
    for run, row in zip(runs, rows):
        sim.reset()
        first = sim.positions[tip].copy()
        levels = {k[len("levels."):]: v for k, v in run.params.items() if k.startswith("levels.")}
        release = run.params.get("release_s", np.inf)
        iterations = 0
        for k in range(1, 9):
            figures = sim.step(levels if k * sim.dt <= release + 1e-9
                               else {name: 0.0 for name in levels})
            iterations += figures.iterations
        d = sim.positions[tip] - first
        assert (row["tip_dx_m"], row["tip_dy_m"], row["tip_dz_m"]) == tuple(d)
        assert row["newton_iterations"] == iterations
        assert row["steps"] == 8 and row["simulated_s"] == sim.time
    # And the sweep tool's own sequential mode gives the same table.
    sequential = Sweep(tmp_path / "sequential", None).run(runs)
    assert repeatable(sequential) == repeatable(rows)
    with open(tmp_path / "cluster" / "results.csv") as a, \
            open(tmp_path / "sequential" / "results.csv") as b:
        assert a.readline() == b.readline()  # the same columns


def test_short_runs_share_tasks_and_keep_their_own_rows(client, tmp_path):
    # Runs of a few ms each: after the first wave, one run a task, the next tasks take several.
    runs = make_runs([{"scene": SG_3N, "steps": 2, "levels.SG": round(0.01 * (i + 1), 6)}
                      for i in range(16)])
    sweep = Sweep(tmp_path / "cluster", client)
    rows = sweep.run(runs)
    assert sweep.tasks < len(runs)
    # Each row is its own run's (the levels differ, so do the figures), as done one by one.
    assert repeatable(rows) == repeatable(Sweep(tmp_path / "sequential", None).run(runs))
    assert len({r["tip_dy_m"] for r in rows}) == len(runs)


def test_a_sweep_resumes_after_a_crash_and_skips_what_is_done(client, tmp_path):
    runs = small_runs()
    whole = Sweep(tmp_path / "whole", client).run(runs)

    def crash_at_third_row(row, done, total):
        if done == 3:
            raise Crash("the driver dies here")

    out = tmp_path / "crashed"
    try:
        Sweep(out, client, on_row=crash_at_third_row).run(runs)
        raise AssertionError("the sweep did not crash")
    except Crash:
        pass
    # The three rows reported, and any others of the task that brought the third (a task's
    # rows go to disk together, before they are reported).
    on_disk = sorted(os.listdir(out / "runs"))
    assert 3 <= len(on_disk) < len(runs)
    before = {name: (out / "runs" / name).read_text() for name in on_disk}

    again = Sweep(out, client)
    rows = again.run(runs)
    assert again.skipped == len(on_disk)
    for name, text in before.items():
        assert (out / "runs" / name).read_text() == text  # not run again
    assert repeatable(rows) == repeatable(whole)
    assert len(os.listdir(out / "runs")) == len(runs)


def test_a_killed_sweep_command_resumes(client, tmp_path):
    # The command line against the test's cluster (--scheduler), killed with SIGKILL once two
    # rows are on disk, then run again.
    sweep_file = tmp_path / "sweep.yaml"
    sweep_file.write_text(f"defaults: {{scene: {SG_3N}, steps: 25}}\n"
                          "grid: {levels.SG: [0.02, 0.04, 0.06, 0.08], levels.GGp: [0, 0.05]}\n")
    out = tmp_path / "out"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [os.path.join(PROJECT, "python"), os.path.dirname(tongue.__file__)]))
    command = [sys.executable, "-m", "tongue_sweep", str(sweep_file), "--out", str(out),
               "--scheduler", client.scheduler.address, "--quiet"]
    process = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    rows_dir = out / "runs"
    while process.poll() is None:
        if rows_dir.exists() and len([n for n in os.listdir(rows_dir)
                                      if n.endswith(".json")]) >= 2:
            process.send_signal(signal.SIGKILL)
            break
        time.sleep(0.005)
    process.wait()
    kept = {n: (rows_dir / n).read_text() for n in os.listdir(rows_dir) if n.endswith(".json")}
    assert len(kept) >= 2
    for text in kept.values():
        assert json.loads(text)["status"] == "ok"  # whole rows only

    done = subprocess.run(command, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert f"8 runs: {len(kept)} done before, {8 - len(kept)} now, 0 failed" in done.stdout
    for name, text in kept.items():
        assert (rows_dir / name).read_text() == text
    whole = Sweep(tmp_path / "whole", client).run(
        make_runs([{"scene": SG_3N, "steps": 25, "levels.SG": sg, "levels.GGp": ggp}
                   for sg in (0.02, 0.04, 0.06, 0.08) for ggp in (0, 0.05)]))
    resumed = [json.loads((rows_dir / f"{r['key']}.json").read_text()) for r in whole]
    assert repeatable(resumed) == repeatable(whole)


def test_a_failing_run_lands_in_its_row_and_is_tried_again(client, tmp_path):
    runs = make_runs([{"scene": SG_3N, "steps": 3, "levels.SG": 0.1},
                      {"scene": SG_3N, "steps": 3, "levels.SG": 1.5},        # out of [0, 1]
                      {"scene": SG_3N, "steps": 3, "levels.NOPE": 0.1},      # no such muscle
                      {"scene": "/nonexistent/scene.yaml", "steps": 3},
                      {"scene": SG_3N, "steps": 3, "levels.GGp": 0.1}])
    sweep = Sweep(tmp_path, client)
    rows = sweep.run(runs)
    assert [r["status"] for r in rows] == ["ok", "failed", "failed", "failed", "ok"]
    assert rows[1]["error"].startswith("ValueError")
    assert "NOPE" in rows[2]["error"]
    assert rows[3]["error"].startswith("RuntimeError") and "nonexistent" in rows[3]["error"]
    assert rows[0]["error"] == "" and rows[0]["tip_dy_m"] != 0.0
    with open(tmp_path / "results.csv") as f:
        assert "ValueError" in f.read()
    again = Sweep(tmp_path, client, hdf5=True)
    rows = again.run(runs)
    assert again.skipped == 2  # the failed ones are run again, and fail again
    with h5py.File(tmp_path / "results.h5", "r") as f:
        assert list(f.attrs["columns"])[:4] == ["key", "kind", "status", "error"]
        assert [s.decode() for s in f["status"][:]] == [r["status"] for r in rows]
        assert np.isnan(f["tip_dy_m"][1]) and f["tip_dy_m"][0] == rows[0]["tip_dy_m"]
    assert [r["status"] for r in rows] == ["ok", "failed", "failed", "failed", "ok"]
