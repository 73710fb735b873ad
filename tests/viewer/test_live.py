"""tongue_viewer in live mode beside a lock-step sim_server driven by sequence_player, with the
page in headless Chromium; and the viewer or the browser going away in the middle of a run,
which must not disturb the run."""
import re

import numpy as np
import pytest

from conftest import (RUN_TIMEOUT_S, START_TIMEOUT_S, assert_drawn, lcm_url, project_path,
                      read_run, wait_until)

SG_3N = project_path("controllers", "sequences", "sg_3n.yaml")  # 30 steps of 4 ms
SG_LEVEL = 3.0 / 24.0  # 3 N over SG_left and SG_right, split by F_max (sg_3n.yaml)


def numbers(text):
    return [int(n) for n in re.findall(r"-?\d+", text or "")]


def long_schedule(folder, duration_s):
    """sg_3n.yaml's 120 ms SG step, the run going on to duration_s: long enough (thousands of
    lock-step steps) that the viewer or the browser is surely gone before it ends."""
    path = folder / "long_sg.yaml"
    path.write_text(f"duration: {duration_s}\n"
                    "entries:\n"
                    "  - {muscle: SG, start: 0.0, end: 0.12, force: 3.0}\n")
    return str(path)


def assert_complete_run(path, steps, dt=0.004):
    run = read_run(path)
    assert run["status"] == "completed"
    assert run["positions"].shape[0] == steps + 1, "the run file lacks frames"
    np.testing.assert_allclose(run["time"], np.arange(steps + 1) * dt, rtol=0, atol=1e-9)
    assert np.all(np.isfinite(run["positions"]))
    sg = [run["muscles"].index(n) for n in ("SG_left", "SG_right")]
    np.testing.assert_allclose(run["activations"][1:30, sg], SG_LEVEL)  # the player's step
    if steps > 40:
        assert np.all(run["activations"][40:] == 0.0)  # after the step, all off


def test_live_page_follows_a_lockstep_run(tmp_path, processes, browser):
    port = 7870
    # The viewer first: with no server on its bus it has no model, says so, and waits.
    viewer = processes.viewer("--lcm-url", lcm_url(port), "--listen", "127.0.0.1:0")
    code, body = viewer.get("/api/model")
    assert code == 404 and "no model yet" in body["error"], body
    code, session = viewer.get("/api/session")
    assert code == 200 and session["mode"] == "live" and session["runs"] == [], session
    page = browser.page
    page.load(viewer.url)
    wait_until(lambda: (page.status_text() or "").strip(), START_TIMEOUT_S,
               "the page's status line to say something while there is no model")

    server = processes.sim_server(port, "tongue_sg_3n.yaml", tmp_path / "run.h5",
                                  "--max-steps", "30")
    page.wait_ready()  # the model and the first state (step 0: no controller yet)
    info = page.info()
    assert info["mode"] == "live" and info["step"] == 0, info
    assert info["framesDrawn"] >= 1 and info["modelVersion"] is not None, info
    colours, fraction = assert_drawn(browser.element_png("view3d"), "the 3D view (#view3d)")
    print(f"#view3d at step 0: {colours} colours, {fraction:.1%} of it drawn")
    assert_drawn(browser.element_png("view2d"), "the 2D view (#view2d)", min_colours=2,
                 min_fraction=0.002)
    assert 0 in numbers(page.text("step")), page.text("step")
    activations = page.text("activations")
    for muscle in read_run_muscles(tmp_path, viewer):
        assert muscle in activations, f"no activation bar labelled {muscle}: {activations!r}"

    player = processes.sequence_player(port, SG_3N)
    # The page asks for the newest state after each frame drawn: it ends on the last one.
    wait_until(lambda: page.info()["step"] == 30, RUN_TIMEOUT_S, "the page to show step 30")
    wait_until(lambda: 30 in numbers(page.text("step")), START_TIMEOUT_S, "#step to show 30")
    wait_until(lambda: 120 in numbers(page.text("time")), START_TIMEOUT_S,
               "#time to show 120 (ms)")
    for element in ("rtf", "iterations"):
        assert (page.text(element) or "").strip(), f"#{element} is empty"
    last = page.info()
    assert last["framesDrawn"] > info["framesDrawn"] and last["time"] == pytest.approx(0.12)
    assert player.wait() == 0, player.stderr()
    assert server.wait() == 0, server.stderr()
    assert_drawn(browser.element_png("view3d"), "the 3D view at step 30")
    assert viewer.running()
    assert viewer.terminate() == 130, viewer.stderr()  # SIGTERM: the contract's status


def read_run_muscles(tmp_path, viewer):
    """The 19 muscle names, from the model the viewer serves."""
    code, model = viewer.get("/api/model")
    assert code == 200, model
    names = [m["name"] for m in model["muscles"]]
    assert len(names) == 19 and "GGp_left" in names, names
    return names


def test_viewer_killed_mid_run_leaves_the_run_whole(tmp_path, processes, browser):
    port, steps = 7871, 4000
    server = processes.sim_server(port, "tongue_sg_3n.yaml", tmp_path / "run.h5",
                                  "--max-steps", str(steps))
    viewer = processes.viewer("--lcm-url", lcm_url(port), "--listen", "127.0.0.1:0")
    # A second viewer on the same server: any number may watch it.
    other = processes.viewer("--lcm-url", lcm_url(port), "--listen", "127.0.0.1:0",
                             name="second tongue_viewer")
    browser.page.open(viewer.url)  # joins late: asks the server to describe itself
    wait_until(lambda: other.get("/api/model")[0] == 200, START_TIMEOUT_S,
               "the second viewer to have the model")
    player = processes.sequence_player(port, long_schedule(tmp_path, steps * 0.004),
                                       "--timeout-s", str(RUN_TIMEOUT_S))
    wait_until(lambda: browser.page.info()["step"] >= 1, RUN_TIMEOUT_S,
               "the page to show a step of the run")
    # The controller held while the viewer goes, so that it surely goes mid-run (the page once
    # showed its first step only 545 steps before the end): the lock-step server waits for it.
    player.pause()
    try:
        status_before = browser.page.status_text()
        viewer.kill()  # SIGKILL: no goodbye on the bus or to the page
        print(f"viewer killed with the page at step {browser.page.info()['step']} of {steps}")
        assert player.running() and server.running(), "the run ended before the viewer went"
    finally:
        player.resume()
    assert player.wait() == 0, player.stderr()
    assert server.wait() == 0, server.stderr()
    assert_complete_run(tmp_path / "run.h5", steps)
    assert other.running() and other.get("/api/model")[1]["version"] == 1, other.stderr()
    # The page notices that its server is gone.
    wait_until(lambda: (browser.page.status_text() or "").strip() not in
               ("", (status_before or "").strip()), START_TIMEOUT_S,
               f"the page's status line (was {status_before!r}) to report the lost viewer")


def test_browser_closed_mid_run_leaves_the_run_and_the_viewer_whole(tmp_path, processes,
                                                                     browser_factory):
    port, steps = 7872, 4000
    server = processes.sim_server(port, "tongue_sg_3n.yaml", tmp_path / "run.h5",
                                  "--max-steps", str(steps))
    viewer = processes.viewer("--lcm-url", lcm_url(port), "--listen", "127.0.0.1:0")
    first = browser_factory()
    first.page.open(viewer.url)
    # The player's silence limit above the longest the browser may take to close (it is held
    # meanwhile, below).
    player = processes.sequence_player(port, long_schedule(tmp_path, steps * 0.004),
                                       "--timeout-s", str(RUN_TIMEOUT_S))
    wait_until(lambda: first.page.info()["step"] >= 1, RUN_TIMEOUT_S,
               "the page to show a step of the run")
    # The controller held while the browser goes: the lock-step server waits for it (publishing
    # its state again), so the browser surely goes in the middle of the run, however long
    # closing it takes (once longer than the 2.5 s the rest of the run took).
    player.pause()
    try:
        shown = first.page.info()["step"]
        first.close()  # the browser goes, its WebSocket with it
        print(f"browser closed at step {shown} of {steps}")
        assert player.running() and server.running(), "the run ended before the browser closed"
    finally:
        player.resume()
    assert viewer.get("/api/session")[0] == 200
    assert player.wait() == 0, player.stderr()
    assert server.wait() == 0, server.stderr()
    assert_complete_run(tmp_path / "run.h5", steps)
    # The viewer lives on: a new page gets the model and the last state.
    assert viewer.running(), viewer.stderr()
    second = browser_factory()
    second.page.open(viewer.url)
    wait_until(lambda: second.page.info()["step"] == steps, START_TIMEOUT_S,
               f"the new page to show the last step, {steps}")
    assert_drawn(second.element_png("view3d"), "the new page's 3D view")
