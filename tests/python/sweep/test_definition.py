"""The sweep file: grids, runs, keys, CSV."""
import pytest

from conftest import SG_3N
from tongue_sweep import make_runs, parse_ports
from tongue_sweep.definition import read_sweep, run_key


def test_a_grid_gives_every_combination_over_the_defaults(tmp_path):
    path = tmp_path / "sweep.yaml"
    path.write_text(f"defaults: {{scene: {SG_3N}, steps: 5}}\n"
                    "grid: {levels.SG: [0.05, 0.1], levels.GGp: [0, 0.1, 0.2]}\n"
                    "runs: [{levels: {SG: 0.2}, steps: 8}]\n")
    runs = read_sweep(str(path))
    assert len(runs) == 7
    assert runs[0].params == {"scene": SG_3N, "steps": 5, "levels.SG": 0.05, "levels.GGp": 0,
                              "kind": "simulation"}
    assert runs[-1].params["levels.SG"] == 0.2 and runs[-1].params["steps"] == 8
    assert len({r.key for r in runs}) == 7


def test_keys_ignore_order_and_int_or_float():
    assert run_key({"a": 1, "b": "x"}) == run_key({"b": "x", "a": 1.0})
    assert run_key({"a": 1}) != run_key({"a": 2})


def test_csv_paths_are_resolved_against_the_file(tmp_path):
    path = tmp_path / "sweep.csv"
    path.write_text("# a comment\nscene,steps,levels.SG\nscene.yaml,5,0.1\nscene.yaml,5,\n")
    runs = read_sweep(str(path))
    assert runs[0].params["scene"] == str(tmp_path / "scene.yaml")
    assert runs[0].params["levels.SG"] == 0.1 and runs[0].params["steps"] == 5
    assert "levels.SG" not in runs[1].params


def test_the_same_run_twice_and_a_run_without_scene_are_refused():
    with pytest.raises(ValueError, match="same parameters"):
        make_runs([{"scene": SG_3N, "steps": 1}, {"scene": SG_3N, "steps": 1.0}])
    with pytest.raises(ValueError, match="needs 'scene'"):
        make_runs([{"steps": 1}])


def test_port_ranges():
    assert parse_ports("7985-7987,7990") == [7985, 7986, 7987, 7990]
    with pytest.raises(ValueError):
        parse_ports("7985-7986,7986")
