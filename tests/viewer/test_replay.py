"""tongue_viewer replaying run files made by sim_batch: what it serves, and what the page shows
after the slider moves or tongueViewer.seek, against the run file read with h5py."""
import os

import h5py
import numpy as np
import pytest

from conftest import (POSITION_ATOL_M, START_TIMEOUT_S, assert_drawn, assert_positions_equal,
                      read_run, sim_batch, wait_until)


def replay(processes, *paths):
    args = []
    for path in paths:
        args += ["--run", path]
    return processes.viewer(*args, "--listen", "127.0.0.1:0")


def test_session_model_and_frames_are_the_run_files(runs, processes):
    viewer = replay(processes, runs["sg"])
    run = read_run(runs["sg"])
    code, session = viewer.get("/api/session")
    assert code == 200 and session["mode"] == "replay", session
    assert len(session["runs"]) == 1
    entry = session["runs"][0]
    assert entry["name"] == "sg.h5" and entry["path"] == os.path.abspath(runs["sg"]), entry
    assert entry["frames"] == 31 and entry["status"] == "completed", entry
    assert entry["analysis"] == "dynamic", entry
    np.testing.assert_allclose(entry["times"], run["time"], rtol=0, atol=1e-12)

    code, model = viewer.get("/api/model?run=0")
    assert code == 200 and model["num_nodes"] == 1001, model.get("num_nodes")
    assert_positions_equal(model["rest_positions"], run["rest_positions"])
    assert len(model["elements"]) == 8 * 720 and len(model["surface"]) % 4 == 0
    assert 0 <= min(model["surface"]) and max(model["surface"]) < 1001
    assert [m["name"] for m in model["muscles"]] == run["muscles"]
    assert {m["name"] for m in model["landmarks"]} == {
        "tip", "blade", "palatal_dorsum", "velar_dorsum", "root", "gg_insertion"}
    assert model["dt"] == pytest.approx(0.004)

    code, frame = viewer.get("/api/frame?run=0&index=12")
    assert code == 200 and frame["type"] == "frame", frame
    assert (frame["run"], frame["index"], frame["nodes"]) == (0, 12, None)
    assert frame["time"] == pytest.approx(run["time"][12], abs=1e-12)
    error = assert_positions_equal(frame["positions"], run["positions"][12])
    print(f"/api/frame: positions within {error:.3g} m of the run file")
    assert len(frame["activations"]) == 19

    # Out of range: 404 with an error (the contract); a negative index or a run that is not
    # there may also be refused as a bad request.
    for bad, codes in (("/api/frame?run=0&index=31", (404,)),
                       ("/api/frame?run=0&index=-1", (400, 404)),
                       ("/api/frame?run=1&index=0", (400, 404))):
        code, body = viewer.get(bad)
        assert code in codes and isinstance(body, dict) and body.get("error"), (bad, code, body)


def set_slider(driver, fraction):
    """Moves #slider to min + fraction (max - min) as a user would: value, then 'input'."""
    return driver.execute_script(
        "const s = document.getElementById('slider');"
        "const min = Number(s.min), max = Number(s.max);"
        "s.value = String(min + (max - min) * arguments[0]);"
        "s.dispatchEvent(new Event('input', {bubbles: true}));"
        "s.dispatchEvent(new Event('change', {bubbles: true}));"
        "return {min: s.min, max: s.max, value: s.value};", fraction)


def test_slider_and_seek_show_the_run_files_positions(runs, processes, browser):
    viewer = replay(processes, runs["sg"])
    run = read_run(runs["sg"])
    times, last = run["time"], len(run["time"]) - 1
    page = browser.page
    page.open(viewer.url)
    info = page.info()
    assert info["mode"] == "replay" and info["index"] == 0, info
    assert_positions_equal(page.positions(), run["positions"][0])
    assert_drawn(browser.element_png("view3d"), "the 3D view (#view3d) at frame 0")

    # The slider at its end: the last frame; halfway: some frame between, the run file's.
    slider = set_slider(browser.driver, 1.0)
    wait_until(lambda: page.info()["index"] == last, START_TIMEOUT_S,
               f"the page to show the last frame after the slider moved to {slider}")
    info = page.info()
    assert info["time"] == pytest.approx(times[last], abs=1e-12), info
    error = assert_positions_equal(page.positions(), run["positions"][last])
    print(f"page positions within {error:.3g} m of the run file")
    wait_until(lambda: str(info["step"]) in page.text("step"), START_TIMEOUT_S,
               f"#step to show step {info['step']}")
    slider = set_slider(browser.driver, 0.5)
    wait_until(lambda: page.info()["index"] != last, START_TIMEOUT_S,
               f"the page to move off the last frame after the slider moved to {slider}")
    info = page.info()
    assert 0 < info["index"] < last, (slider, info)
    assert info["time"] == pytest.approx(times[info["index"]], abs=1e-12), info
    assert_positions_equal(page.positions(), run["positions"][info["index"]])

    # seek: the frame nearest the time, drawn when its Promise resolves. Neighbouring frames
    # differ by far more than the tolerance, so the right frame is told from its neighbours.
    dt = times[1] - times[0]
    for k in (7, 9, 22):
        assert np.abs(run["positions"][k + 1] - run["positions"][k]).max() > 100 * POSITION_ATOL_M
    for t, index in ((times[7], 7), (times[22], 22), (times[9] + 0.4 * dt, 9),
                     (times[9] + 0.6 * dt, 10), (-1.0, 0), (10.0, last)):
        info = page.seek(t)
        assert info["index"] == index, (t, info)
        assert_positions_equal(page.positions(), run["positions"][index])

    # setView redraws; the picture is still there.
    page.set_view(view="3d", field="displacement", camera="front")
    assert_drawn(browser.element_png("view3d"), "the 3D view after setView")


def test_start_time_from_the_url(runs, processes, browser):
    viewer = replay(processes, runs["sg"])
    run = read_run(runs["sg"])
    browser.page.open(viewer.url + "?time=0.06&view=both&field=activation&camera=oblique")
    wait_until(lambda: browser.page.info()["index"] == 15, START_TIMEOUT_S,
               "the page to show frame 15 (t = 0.06 s, from the URL)")
    assert_positions_equal(browser.page.positions(), run["positions"][15])


@pytest.mark.parametrize("compare", ["", "?compare=side"])
def test_two_runs_each_at_its_frame_nearest_the_time(runs, processes, browser, compare):
    viewer = replay(processes, runs["sg"], runs["ggp"])
    sg, ggp = read_run(runs["sg"]), read_run(runs["ggp"])
    code, session = viewer.get("/api/session")
    assert [r["name"] for r in session["runs"]] == ["sg.h5", "ggp.h5"], session
    assert viewer.get("/api/model?run=1")[0] == 200
    page = browser.page
    page.open(viewer.url + compare)
    for k in (0, 13, 30):
        page.seek(sg["time"][k])
        assert page.info()["index"] == k
        assert_positions_equal(page.positions(0), sg["positions"][k])
        assert_positions_equal(page.positions(1), ggp["positions"][k])
    # The two runs really differ there (else the check above proves little).
    assert np.abs(sg["positions"][30] - ggp["positions"][30]).max() > 1e-4
    assert_drawn(browser.element_png("view3d"), "the 3D view of two runs")


def test_contact_scene_obstacles_and_contacts_are_the_run_files(tmp_path, processes, browser):
    """The /k/ closure against the built-in vocal tract (50 steps): the model's four obstacles,
    and a frame's contacts (obstacle -1 in replay: the run file does not say which), forces and
    penetration as the run file has them."""
    path = sim_batch("tongue_k.yaml", tmp_path / "k.h5")
    with h5py.File(path, "r") as f:
        node_force = f["contact/node_force"][:]
        obstacle_force = f["contact/obstacle_force"][:]
        penetration = f["contact/max_penetration"][:]
        positions = f["positions"][:]
    touching = np.linalg.norm(node_force, axis=2)
    k = int(np.argmax((touching > 0).sum(axis=1)))  # the frame with the most contacts
    assert (touching[k] > 0).sum() >= 5, "the /k/ scene no longer reaches the palate"
    viewer = replay(processes, path)
    code, model = viewer.get("/api/model?run=0")
    assert code == 200
    assert [o["name"] for o in model["obstacles"]] == [
        "hard_palate", "upper_teeth", "velum", "pharyngeal_wall"], model["obstacles"][:1]
    for o in model["obstacles"]:
        assert len(o["vertices"]) % 3 == 0 and len(o["triangles"]) % 3 == 0 and o["triangles"]
        assert max(o["triangles"]) < len(o["vertices"]) // 3, o["name"]

    code, frame = viewer.get(f"/api/frame?run=0&index={k}")
    assert code == 200
    contacts = frame["contacts"]
    nodes = contacts["nodes"]
    assert set(np.flatnonzero(touching[k] > 1e-9)) <= set(nodes) <= set(
        np.flatnonzero(touching[k] > 0)), (nodes, np.flatnonzero(touching[k] > 0))
    assert contacts["obstacles"] == [-1] * len(nodes)
    scale = np.abs(node_force[k]).max()
    np.testing.assert_allclose(np.reshape(contacts["forces"], (-1, 3)), node_force[k][nodes],
                               rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(frame["obstacle_forces"], obstacle_force[k].ravel(), rtol=0,
                               atol=1e-6 * np.abs(obstacle_force[k]).max())
    assert frame["max_penetration"] == pytest.approx(penetration[k], abs=1e-9)

    page = browser.page
    page.open(viewer.url)
    assert page.seek(float(frame["time"]))["index"] == k
    assert_positions_equal(page.positions(), positions[k])
    assert_drawn(browser.element_png("view3d"), "the 3D view with the vocal tract")
    assert_drawn(browser.element_png("view2d"), "the 2D view with the vocal tract",
                 min_colours=2, min_fraction=0.002)
