"""Whole run_experiment runs in a sweep, in parallel on udpm ports 7985-7986 (the range the
tests may use), with a changed plan and duration."""
import os

import pytest

from conftest import AI
from tongue_sweep import Sweep, make_runs
from tongue_sweep.experiment_job import find_run_experiment


@pytest.fixture(scope="module")
def runner():
    try:
        return find_run_experiment()
    except RuntimeError:
        pytest.skip("run_experiment not built")


def test_experiment_runs_with_changed_plans_on_ports_of_their_own(client, runner, tmp_path):
    # /a/ reached at 50 ms: GGa's first target changes the tip's descent within 0.1 s.
    runs = make_runs([{"experiment": AI, "duration_s": 0.1, "plan.delta_lambda_mm.GGa.0": v}
                      for v in (-10, -5, 0)])
    rows = Sweep(tmp_path, client, ports=[7985, 7986], runner=runner).run(runs)
    assert [r["status"] for r in rows] == ["ok"] * 3, [r["error"] for r in rows]
    assert {r["port"] for r in rows} <= {7985, 7986}
    assert [r["steps"] for r in rows] == [13] * 3  # 0.1 s at dt 8 ms, rounded to whole steps
    tip_dy = [r["tip_dy_m"] for r in rows]
    assert tip_dy[0] < tip_dy[1] < tip_dy[2]  # GGa pulling harder draws the tip further down
    with open(os.path.join(rows[0]["run_folder"], "..", "inputs", "plan_ep.yaml")) as f:
        assert "- -10" in f.read()


def test_a_plan_entry_that_is_not_there_fails_its_run(client, runner, tmp_path):
    runs = make_runs([{"experiment": AI, "duration_s": 0.1, "plan.delta_lambda_mm.XX.0": -5}])
    row = Sweep(tmp_path, client, ports=[7987], runner=runner).run(runs)[0]
    assert row["status"] == "failed" and "delta_lambda_mm.XX.0" in row["error"]


def test_runs_that_need_no_port_go_while_the_experiments_wait_for_one(client, runner, tmp_path):
    # Two experiments on one port, listed before three simulation runs: the second experiment
    # waits for the port, the simulations do not wait for it, and every row is its run's.
    from conftest import SG_3N
    runs = make_runs([{"experiment": AI, "duration_s": 0.05, "plan.delta_lambda_mm.GGa.0": v}
                      for v in (-10, 0)] +
                     [{"scene": SG_3N, "steps": 3, "levels.SG": s} for s in (0.05, 0.1, 0.15)])
    arrived = []
    rows = Sweep(tmp_path / "mixed", client, ports=[7987], runner=runner,
                 on_row=lambda row, done, total: arrived.append(row["kind"])).run(runs)
    assert [r["status"] for r in rows] == ["ok"] * 5, [r["error"] for r in rows]
    # A simulation of three steps on the idle worker ends long before the first experiment (a
    # run_experiment of three processes): had the simulations waited behind the experiment for
    # the port, none would come back first.
    assert arrived[0] == "simulation", arrived
    assert [r["port"] for r in rows[:2]] == [7987, 7987]
    alone = Sweep(tmp_path / "alone", None).run(runs[2:])
    assert [r["tip_dy_m"] for r in rows[2:]] == [r["tip_dy_m"] for r in alone]
