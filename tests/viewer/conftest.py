"""Fixtures of tongue_viewer's browser tests: real processes (sim_server, sequence_player,
sim_batch, tongue_viewer) and headless Chromium through Selenium, all stopped after each test
whatever happened.

The programs come from the environment (CTest sets them, tests/viewer/CMakeLists.txt): SIM_SERVER,
SEQUENCE_PLAYER, SIM_BATCH, TONGUE_VIEWER, PROJECT_DIR; without them, PROJECT_DIR defaults to this
source tree and the programs to the build folder BUILD_DIR (default PROJECT_DIR/build). From a
second work tree against the main one's build: BUILD_DIR=/work/main/build python3 -m pytest ...
VIEWER_WEB=DIR, when set, gives the viewer (and render_run.py) the page's folder with --web.

Waits are on conditions with generous deadlines (a loaded 2-core machine, Chromium drawing WebGL
in software): a slow machine makes the tests slower, never wrong. Each LCM test has a udpm port of
its own in 7870-7879; HTTP is on port 0 (the viewer picks a free port and prints it).
"""
import io
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

PROJECT = os.environ.get("PROJECT_DIR") or os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree's scripts/
sys.path.insert(0, os.path.join(PROJECT, "scripts"))
import render_run  # noqa: E402  (Browser, Page and the serving line, shared with the stills)

BUILD = os.environ.get("BUILD_DIR") or os.path.join(PROJECT, "build")
PROGRAMS = {
    "SIM_SERVER": os.path.join(BUILD, "sim_server", "apps", "sim_server"),
    "SIM_BATCH": os.path.join(BUILD, "sim_server", "apps", "sim_batch"),
    "SEQUENCE_PLAYER": os.path.join(BUILD, "controllers", "sequence_player", "sequence_player"),
    "TONGUE_VIEWER": os.path.join(BUILD, "viewer", "tongue_viewer"),
}

# Deadlines (s). None of them is a pace the tests expect: each bounds a wait for something that
# takes well under a second alone.
START_TIMEOUT_S = 60      # a program printing its first line, a page getting ready
RUN_TIMEOUT_S = 300       # a whole lock-step run with a viewer and a browser beside it
STOP_TIMEOUT_S = 15       # a program ending after SIGTERM
POLL_S = 0.05

# Positions shown by the page (or served as JSON) against the run file's float64. The contract
# does not fix the JSON's precision; the server writes positions rounded to 1e-8 m (10 nm, within
# 5e-9 m), and the page may hold them in a Float32Array for WebGL (relative rounding 2^-24, 6e-9 m
# at 0.1 m). Hence within 1e-8 m + 2^-23 of each value: five orders of magnitude below the
# tongue's millimetres, and far below a node's motion from one frame to the next (the tests check
# that the frames they compare differ by more).
POSITION_RTOL = 2.0 ** -23
POSITION_ATOL_M = 1e-8


def program(name):
    return os.environ.get(name) or PROGRAMS[name]


def web_args():
    """--web DIR when VIEWER_WEB is set, else nothing (the viewer's own page)."""
    return ["--web", os.environ["VIEWER_WEB"]] if os.environ.get("VIEWER_WEB") else []


def project_path(*parts):
    return os.path.join(PROJECT, *parts)


def lcm_url(port):
    """The project's default bus URL on `port`, with its 4 MB receive buffer. The kernel's
    default (208 KiB) holds only a handful of the tongue's 24 kB states: a viewer starved of CPU
    beside the browser can fall that far behind a lock-step run of 2 ms steps, and the states
    that arrive then are dropped, the last one among them (one CI run waited 300 s for a page to
    show step 30)."""
    assert 7870 <= port <= 7879, "the viewer tests own udpm ports 7870-7879 only"
    return f"udpm://239.255.76.67:{port}?ttl=0&recv_buf_size=4194304"


def wait_until(condition, timeout_s, what):
    """Polls condition() until it returns something truthy, which it returns; fails naming
    `what` after timeout_s."""
    deadline = time.monotonic() + timeout_s
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            pytest.fail(f"timed out after {timeout_s} s waiting for {what}")
        time.sleep(POLL_S)


class Process:
    """A started program; its stdout and stderr go to files (never a pipe that could fill)."""

    def __init__(self, name, command, folder, env=None):
        self.name = name
        self.command = [str(c) for c in command]
        self.stdout_path = os.path.join(folder, f"{name}.stdout")
        self.stderr_path = os.path.join(folder, f"{name}.stderr")
        with open(self.stdout_path, "wb") as out, open(self.stderr_path, "wb") as err:
            self.popen = subprocess.Popen(self.command, stdout=out, stderr=err,
                                          stdin=subprocess.DEVNULL, env=env)
        self.pid = self.popen.pid

    def stdout(self):
        return render_run.read_text(self.stdout_path)

    def stderr(self):
        return render_run.read_text(self.stderr_path)

    def running(self):
        return self.popen.poll() is None

    def wait(self, timeout_s=RUN_TIMEOUT_S):
        """Its exit status; fails the test if it does not end within timeout_s."""
        try:
            return self.popen.wait(timeout_s)
        except subprocess.TimeoutExpired:
            pytest.fail(f"{self.name} did not end within {timeout_s} s; stderr:\n"
                        f"{self.stderr()[-2000:]}")

    def pause(self):
        """SIGSTOP: it holds where it is until resume()."""
        self.popen.send_signal(signal.SIGSTOP)

    def resume(self):
        self.popen.send_signal(signal.SIGCONT)

    def terminate(self):
        """SIGTERM and wait; its exit status."""
        if self.running():
            self.popen.send_signal(signal.SIGTERM)
        return self.wait(STOP_TIMEOUT_S)

    def kill(self):
        if self.running():
            self.popen.kill()
        self.popen.wait()

    def stop(self):
        """Cleanup: SIGTERM, then SIGKILL if it lingers."""
        if self.running():
            self.popen.send_signal(signal.SIGTERM)
            try:
                self.popen.wait(STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                self.popen.kill()
                self.popen.wait()

    def report(self):
        return (f"--- {self.name} (exit {self.popen.poll()}): {' '.join(self.command)}\n"
                f"stdout:\n{self.stdout()[-3000:]}\nstderr:\n{self.stderr()[-3000:]}")


class Viewer(Process):
    """tongue_viewer; started() waits for its serving line and sets url and port."""

    url = None
    port = None

    def started(self, timeout_s=START_TIMEOUT_S):
        def serving():
            for line in self.stdout().splitlines():
                match = render_run.SERVING.match(line)
                if match:
                    return match
            if not self.running():
                pytest.fail(f"tongue_viewer exited with {self.popen.returncode} before serving; "
                            f"stderr: {self.stderr()}")
            return None
        match = wait_until(serving, timeout_s, "tongue_viewer's 'serving http://...' line")
        self.url, self.port = match.group(1), int(match.group(2))
        return self

    def get(self, path, timeout_s=30):
        """(HTTP status, parsed JSON body) of GET path."""
        import json
        import urllib.error
        import urllib.request
        try:
            with urllib.request.urlopen(self.url.rstrip("/") + path, timeout=timeout_s) as r:
                return r.status, json.loads(r.read().decode("utf-8"))
        except urllib.error.HTTPError as e:
            body = e.read().decode("utf-8", "replace")
            try:
                return e.code, json.loads(body)
            except ValueError:
                return e.code, body


class Processes:
    """The programs a test starts, each stopped at its end (in reverse order)."""

    def __init__(self, folder):
        self.folder = str(folder)
        self.started = []

    def start(self, name, command, cls=Process, env=None):
        process = cls(name, command, self.folder, env)
        self.started.append(process)
        return process

    def sim_server(self, port, scene, output, *args):
        return self.start("sim_server", [program("SIM_SERVER"), project_path("scenes", scene),
                                         "--lcm-url", lcm_url(port), "--output", output, *args])

    def sequence_player(self, port, schedule, *args):
        return self.start("sequence_player", [program("SEQUENCE_PLAYER"), "--schedule", schedule,
                                              "--lcm-url", lcm_url(port), *args])

    def viewer(self, *args, name="tongue_viewer"):
        return self.start(name, [program("TONGUE_VIEWER"), *args, *web_args()],
                          cls=Viewer).started()

    def stop_all(self):
        for process in reversed(self.started):
            process.stop()


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    setattr(item, "report_" + report.when, report)


def _failed(request):
    return any(getattr(request.node, "report_" + when, None) is not None
               and getattr(request.node, "report_" + when).failed for when in ("setup", "call"))


@pytest.fixture
def processes(tmp_path, request):
    started = Processes(tmp_path)
    try:
        yield started
    finally:
        started.stop_all()
        if _failed(request):  # shown under "Captured stdout teardown"
            for process in started.started:
                print(process.report())


class BrowserSession:
    """Headless Chromium (render_run.Browser) with the page helper; close() may come early."""

    def __init__(self):
        self.browser = render_run.Browser(1280, 720, page_timeout_s=START_TIMEOUT_S * 2)
        self.driver = self.browser.driver
        self.page = render_run.Page(self.driver)

    def close(self):
        self.browser.close()

    def element_png(self, element_id):
        from selenium.webdriver.common.by import By
        return self.driver.find_element(By.ID, element_id).screenshot_as_png


@pytest.fixture
def browser():
    session = BrowserSession()
    try:
        yield session
    finally:
        session.close()


@pytest.fixture
def browser_factory():
    """More than one browser in a test: each call starts one; all are closed at the end."""
    sessions = []

    def make():
        sessions.append(BrowserSession())
        return sessions[-1]
    try:
        yield make
    finally:
        for session in sessions:
            session.close()


def sim_batch(scene, output):
    done = subprocess.run([program("SIM_BATCH"), project_path("scenes", scene), "--output",
                           str(output), "--quiet"], capture_output=True, text=True,
                          timeout=RUN_TIMEOUT_S)
    assert done.returncode == 0, done.stdout + done.stderr
    return str(output)


@pytest.fixture(scope="session")
def runs(tmp_path_factory):
    """Short real run files made by sim_batch: the paper's 3 N styloglossus step and 4 N
    posterior genioglossus step (120 ms, dt 4 ms: 31 frames each)."""
    folder = tmp_path_factory.mktemp("runs")
    return {"sg": sim_batch("tongue_sg_3n.yaml", folder / "sg.h5"),
            "ggp": sim_batch("tongue_ggp_4n.yaml", folder / "ggp.h5")}


def read_run(path):
    import h5py
    with h5py.File(path, "r") as f:
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["muscles/names"][:]]
        return {"time": f["time"][:], "positions": f["positions"][:],
                "activations": f["activations"][:], "muscles": names,
                "status": f.attrs.get("status"), "rest_positions": f["rest_positions"][:]}


def assert_positions_equal(shown, expected):
    """shown (the page's flat list) equals expected (a run file's N x 3 float64 frame) within
    the rounding of float32 (POSITION_RTOL); returns the largest difference, m."""
    shown = np.asarray(shown, dtype=float)
    expected = np.asarray(expected, dtype=float).ravel()
    assert shown.shape == expected.shape, f"{shown.size} values shown for {expected.size}"
    error = np.abs(shown - expected)
    bound = POSITION_RTOL * np.abs(expected) + POSITION_ATOL_M
    worst = int(np.argmax(error - bound))
    assert np.all(error <= bound), (
        f"position value {worst} (node {worst // 3}, axis {'xyz'[worst % 3]}) is "
        f"{shown[worst]!r}, the run file's {expected[worst]!r}: off by {error[worst]:.3g} m > "
        f"{bound[worst]:.3g} m")
    return float(error.max())


def image_content(png):
    """(width, height, distinct colours, fraction of pixels unlike the most common colour) of a
    PNG's bytes."""
    from PIL import Image
    image = Image.open(io.BytesIO(png) if isinstance(png, bytes) else png).convert("RGB")
    pixels = np.asarray(image).reshape(-1, 3)
    colours, counts = np.unique(pixels, axis=0, return_counts=True)
    return image.width, image.height, len(colours), 1.0 - counts.max() / len(pixels)


def assert_drawn(png, what, min_colours=16, min_fraction=0.01):
    """The picture is not blank: many colours, and at least min_fraction of it unlike its
    background (its most common colour)."""
    width, height, colours, fraction = image_content(png)
    assert width > 0 and height > 0, f"{what}: an empty picture"
    assert colours >= min_colours and fraction >= min_fraction, (
        f"{what} looks blank: {colours} distinct colours, {fraction:.2%} of {width}x{height} "
        f"pixels unlike the background")
    return colours, fraction
