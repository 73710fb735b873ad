#!/usr/bin/python3
"""Stills and a movie of a run file, drawn by tongue_viewer's page in headless Chromium.

usage: render_run.py RUN.h5 [--reference REF.h5] [--times T ... | --every N]
                     [--view both|3d|2d] [--field muscle|activation|displacement]
                     [--camera left|front|top|oblique] [--size 1280x720] [--out DIR]
                     [--mp4 FILE] [--fps F] [--viewer PATH] [--web DIR]

Starts `tongue_viewer --run RUN.h5 [--run REF.h5] --listen 127.0.0.1:0`, reads its port from the
line `tongue_viewer: serving http://127.0.0.1:PORT/`, opens the page in headless Chromium
(SwiftShader WebGL) through Selenium with the view, field and camera as URL parameters, waits
for `window.tongueViewer.ready`, and for each chosen time calls `tongueViewer.seek(t)` and saves
a screenshot of the whole page, SIZE pixels, as DIR/frame_<index>_t<time>s.png (index and time of
the run's frame shown, e.g. frame_00012_t0.048s.png).

Times: --times T ... (s; each shows the run's frame nearest T), else every N-th frame of the run
(--every N, default 1: every frame). --out defaults to RUN_frames/ beside the run file. --mp4
FILE assembles the frames, in the order drawn, at --fps frames per second (default 25) with
ffmpeg (H.264, yuv420p), which must be on PATH. --viewer defaults to $TONGUE_VIEWER, else
build/viewer/tongue_viewer of this project; --web DIR is passed on to it (the page's folder,
default the viewer's own).

Runs on Debian's /usr/bin/python3 (python3-selenium, /usr/bin/chromium, /usr/bin/chromedriver).
The viewer and the browser are stopped on every way out (done, error, SIGINT, SIGTERM).

Exit status: 0 done; 1 bad command line, missing file, the viewer failing to start (its stderr
is shown), the page failing, or --mp4 without ffmpeg on PATH (the project's statuses,
docs/exit_codes.md: 2 means an unconverged step there); 130 interrupted.
"""
import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.parse
import urllib.request

PROG = "render_run.py"
PROJECT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
# Headless Chromium with WebGL through SwiftShader (no GPU), no network of its own, no sandbox
# (root in containers), a fresh profile each time (--user-data-dir is added by Browser).
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--hide-scrollbars"]
SERVING = re.compile(r"^tongue_viewer: serving (http://127\.0\.0\.1:(\d+)/)\s*$")
# Generous: a loaded 2-core machine, SwiftShader drawing in software.
VIEWER_START_TIMEOUT_S = 60
PAGE_TIMEOUT_S = 120


class Failure(Exception):
    """A one-line error for the user; the program then exits 1."""


class Interrupted(BaseException):
    def __init__(self, signum):
        super().__init__(signum)
        self.signum = signum


def _raise_interrupted(signum, _frame):
    raise Interrupted(signum)


def read_text(path):
    """A program's output file so far, as text (bytes that are not UTF-8 replaced)."""
    with open(path, "rb") as f:
        return f.read().decode("utf-8", "replace")


def default_viewer():
    return os.environ.get("TONGUE_VIEWER") or os.path.join(PROJECT, "build", "viewer",
                                                           "tongue_viewer")


class Viewer:
    """tongue_viewer on 127.0.0.1:0; its stdout and stderr go to files in a temporary folder
    (never a pipe that could fill up and block it). stop() ends it (SIGTERM, then SIGKILL)."""

    def __init__(self, program, args, timeout_s=VIEWER_START_TIMEOUT_S, env=None):
        self.folder = tempfile.mkdtemp(prefix="tongue_viewer_")
        self.stdout_path = os.path.join(self.folder, "stdout")
        self.stderr_path = os.path.join(self.folder, "stderr")
        self.process = None
        self.url = None
        self.port = None
        if not os.path.isfile(program) or not os.access(program, os.X_OK):
            shutil.rmtree(self.folder, ignore_errors=True)
            raise Failure(f"no tongue_viewer program at {program} (build it, or give --viewer)")
        try:
            with open(self.stdout_path, "wb") as out, open(self.stderr_path, "wb") as err:
                self.process = subprocess.Popen([program, *args], stdout=out, stderr=err,
                                                stdin=subprocess.DEVNULL, env=env)
            self._wait_for_port(timeout_s)
        except BaseException:
            self.stop()
            raise

    def _wait_for_port(self, timeout_s):
        deadline = time.monotonic() + timeout_s
        while True:
            for line in self.stdout().splitlines():
                match = SERVING.match(line)
                if match:
                    self.url, self.port = match.group(1), int(match.group(2))
                    return
            code = self.process.poll()
            if code is not None:
                lines = [line.strip() for line in self.stderr().splitlines() if line.strip()]
                raise Failure(f"tongue_viewer exited with status {code} before serving: "
                              f"{' | '.join(lines) or '(nothing on stderr)'}")
            if time.monotonic() > deadline:
                raise Failure(f"tongue_viewer printed no 'tongue_viewer: serving http://...' line "
                              f"within {timeout_s} s; stderr: {self.stderr().strip()}")
            time.sleep(0.05)

    def stdout(self):
        return read_text(self.stdout_path)

    def stderr(self):
        return read_text(self.stderr_path)

    def get_json(self, path, timeout_s=30):
        with urllib.request.urlopen(self.url.rstrip("/") + path, timeout=timeout_s) as r:
            return json.loads(r.read().decode("utf-8"))

    def stop(self, timeout_s=10):
        """Ends the viewer if it still runs; returns its exit status."""
        try:
            if self.process is not None and self.process.poll() is None:
                self.process.terminate()
                try:
                    self.process.wait(timeout_s)
                except subprocess.TimeoutExpired:
                    self.process.kill()
                    self.process.wait()
            return None if self.process is None else self.process.returncode
        finally:
            shutil.rmtree(self.folder, ignore_errors=True)


class Browser:
    """Headless Chromium through chromedriver in a process group of its own, with a fresh
    profile; close() quits it and kills whatever of that group is left."""

    def __init__(self, width=1280, height=720, page_timeout_s=PAGE_TIMEOUT_S):
        from selenium import webdriver  # here, so that --help and argument errors need none
        from selenium.webdriver.chrome.service import Service

        self.profile = tempfile.mkdtemp(prefix="tongue_chromium_")
        self.driver = None
        self.service = None
        options = webdriver.ChromeOptions()
        options.binary_location = CHROMIUM
        for arg in [*CHROMIUM_ARGS, f"--user-data-dir={self.profile}",
                    f"--window-size={width},{height}"]:
            options.add_argument(arg)
        self.service = Service(executable_path=CHROMEDRIVER,
                               popen_kw={"start_new_session": True})
        try:
            self.driver = webdriver.Chrome(service=self.service, options=options)
            self.driver.set_script_timeout(page_timeout_s)
            self.driver.set_page_load_timeout(page_timeout_s)
            self.resize(width, height)
        except BaseException:
            self.close()
            raise

    def resize(self, width, height):
        """The page's viewport exactly width x height CSS pixels at 1 device pixel each."""
        self.driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride", {
            "width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})

    def close(self):
        try:
            if self.driver is not None:
                self.driver.quit()
        except Exception:
            pass
        finally:
            self.driver = None
            process = getattr(self.service, "process", None) if self.service else None
            if process is not None:
                try:  # chromedriver leads its own group: Chromium and its helpers are in it
                    os.killpg(process.pid, signal.SIGKILL)
                except (ProcessLookupError, PermissionError):
                    pass
                try:
                    process.wait(10)
                except subprocess.TimeoutExpired:
                    pass
            shutil.rmtree(self.profile, ignore_errors=True)


class Page:
    """The viewer's page in a Browser, through window.tongueViewer."""

    def __init__(self, driver):
        self.driver = driver

    def open(self, url, timeout_s=PAGE_TIMEOUT_S):
        """Loads url and waits for tongueViewer.ready."""
        self.load(url, timeout_s)
        self.wait_ready()

    def load(self, url, timeout_s=PAGE_TIMEOUT_S):
        """Loads url and waits for window.tongueViewer to exist (not for it to be ready)."""
        self.driver.get(url)
        deadline = time.monotonic() + timeout_s
        while not self.driver.execute_script("return typeof window.tongueViewer === 'object' && "
                                             "window.tongueViewer !== null"):
            if time.monotonic() > deadline:
                raise Failure(f"the page {url} defines no window.tongueViewer within "
                              f"{timeout_s} s (status: {self.status_text()!r})")
            time.sleep(0.1)

    def wait_ready(self):
        """Waits for tongueViewer.ready (at most the driver's script timeout); raises Failure
        with the page's status line when it is rejected."""
        result = self.call("return window.tongueViewer.ready")
        if result["error"] is not None:
            raise Failure(f"the page did not get ready: {result['error']} "
                          f"(status: {self.status_text()!r})")

    def call(self, promise_expression, *args):
        """Runs JS whose `return` gives a Promise (or a value), waits for it; returns
        {"value": ..., "error": None | "text"}. arguments[0..] are args."""
        script = ("const done = arguments[arguments.length - 1];"
                  "const f = new Function(" + json.dumps(promise_expression) + ");"
                  "let p; try { p = Promise.resolve(f.apply(null, "
                  "Array.prototype.slice.call(arguments, 0, arguments.length - 1))); }"
                  "catch (e) { done({value: null, error: String(e)}); return; }"
                  "p.then(v => done({value: v === undefined ? null : v, error: null}),"
                  "       e => done({value: null, error: String(e && e.message || e)}));")
        return self.driver.execute_async_script(script, *args)

    def info(self):
        return self.driver.execute_script("return window.tongueViewer.info()")

    def positions(self, run=0):
        return self.driver.execute_script("return Array.from(window.tongueViewer.positions("
                                          "arguments[0]))", run)

    def seek(self, t):
        """Seeks to time t (s); returns info() once drawn."""
        result = self.call("return window.tongueViewer.seek(arguments[0])", float(t))
        if result["error"] is not None:
            raise Failure(f"tongueViewer.seek({t}) failed: {result['error']}")
        return self.info()

    def set_view(self, **view):
        result = self.call("return window.tongueViewer.setView(arguments[0])", view)
        if result["error"] is not None:
            raise Failure(f"tongueViewer.setView({view}) failed: {result['error']}")

    def text(self, element_id):
        return self.driver.execute_script(
            "const e = document.getElementById(arguments[0]); return e ? e.textContent : null",
            element_id)

    def status_text(self):
        try:
            return self.text("status")
        except Exception:
            return None


def parse_size(text):
    match = re.fullmatch(r"(\d+)x(\d+)", text)
    if not match or not (16 <= int(match.group(1)) <= 8192 and 16 <= int(match.group(2)) <= 8192):
        raise argparse.ArgumentTypeError(f"size {text!r} is not WIDTHxHEIGHT (16..8192 each)")
    return int(match.group(1)), int(match.group(2))


def positive_int(text):
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number >= 1")
    return value


def positive_float(text):
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r} is not a number > 0")
    return value


def parse_args(argv):
    p = argparse.ArgumentParser(prog=PROG, description="Stills and a movie of a run file, drawn "
                                "by tongue_viewer's page in headless Chromium.")
    p.add_argument("run", metavar="RUN.h5")
    p.add_argument("--reference", metavar="REF.h5", help="a second run, drawn overlaid")
    which = p.add_mutually_exclusive_group()
    which.add_argument("--times", type=float, nargs="+", metavar="T",
                       help="times (s): each shows the run's frame nearest T")
    which.add_argument("--every", type=positive_int, default=1, metavar="N",
                       help="every N-th frame of the run (default 1)")
    p.add_argument("--view", choices=["both", "3d", "2d"], default="both")
    p.add_argument("--field", choices=["muscle", "activation", "displacement"], default="muscle")
    p.add_argument("--camera", choices=["left", "front", "top", "oblique"], default="left")
    p.add_argument("--size", type=parse_size, default=(1280, 720), metavar="WxH")
    p.add_argument("--out", metavar="DIR", help="folder of the PNGs (default RUN_frames/)")
    p.add_argument("--mp4", metavar="FILE", help="also a movie of the frames (needs ffmpeg)")
    p.add_argument("--fps", type=positive_float, default=25.0)
    p.add_argument("--viewer", metavar="PATH", default=None,
                   help="tongue_viewer program (default $TONGUE_VIEWER, else build/viewer/)")
    p.add_argument("--web", metavar="DIR", default=None,
                   help="the page's folder, passed on to tongue_viewer (default its own)")
    return p.parse_args(argv)


def frame_name(index, t):
    return f"frame_{index:05d}_t{t:.3f}s.png"


def make_movie(ffmpeg, frames, fps, mp4):
    """frames (paths, in order) as an H.264 movie; ffmpeg reads numbered links to them."""
    folder = tempfile.mkdtemp(prefix="render_run_movie_")
    try:
        for k, frame in enumerate(frames):
            os.symlink(os.path.abspath(frame), os.path.join(folder, f"{k:06d}.png"))
        command = [ffmpeg, "-nostdin", "-y", "-loglevel", "error", "-framerate", f"{fps:g}",
                   "-i", os.path.join(folder, "%06d.png"), "-c:v", "libx264",
                   "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", mp4]
        done = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True)
        if done.returncode != 0 or not os.path.isfile(mp4) or os.path.getsize(mp4) == 0:
            lines = done.stderr.strip().splitlines()
            raise Failure(f"ffmpeg failed to write {mp4} (status {done.returncode}): "
                          f"{lines[-1] if lines else 'no message'}")
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def render(args):
    for label, path in (("run file", args.run), ("reference run file", args.reference)):
        if path is not None and not os.path.isfile(path):
            raise Failure(f"no {label} {path}")
    ffmpeg = None
    if args.mp4:
        ffmpeg = shutil.which("ffmpeg")
        if ffmpeg is None:
            raise Failure("--mp4 needs ffmpeg on PATH, which has none (apt-get install ffmpeg); "
                          "no frames were drawn")
    out = args.out or os.path.splitext(args.run)[0] + "_frames"
    program = args.viewer or default_viewer()
    viewer_args = ["--run", os.path.abspath(args.run)]
    if args.reference:
        viewer_args += ["--run", os.path.abspath(args.reference)]
    viewer_args += ["--listen", "127.0.0.1:0"]
    if args.web:
        viewer_args += ["--web", os.path.abspath(args.web)]

    viewer = browser = None
    try:
        viewer = Viewer(program, viewer_args)
        try:
            os.makedirs(out, exist_ok=True)
        except OSError as e:
            raise Failure(f"cannot make the folder {out}: {e.strerror}")
        session = viewer.get_json("/api/session")
        times = session["runs"][0]["times"]
        if not times:
            raise Failure(f"the run file {args.run} has no frames")
        wanted = list(args.times) if args.times else times[::args.every]
        width, height = args.size
        browser = Browser(width, height)
        query = urllib.parse.urlencode({"view": args.view, "field": args.field,
                                        "camera": args.camera})
        page = Page(browser.driver)
        page.open(f"{viewer.url}?{query}")
        written = []
        for t in wanted:
            info = page.seek(t)
            if not isinstance(info, dict) or info.get("index") is None or info.get("time") is None:
                raise Failure(f"tongueViewer.info() after seek({t}) has no index and time: {info}")
            path = os.path.join(out, frame_name(int(info["index"]), float(info["time"])))
            png = browser.driver.get_screenshot_as_png()
            with open(path, "wb") as f:
                f.write(png)
            written.append(path)
        print(f"{PROG}: {len(set(written))} frame(s) of {args.run} in {out}/", flush=True)
        if args.mp4:
            make_movie(ffmpeg, written, args.fps, args.mp4)
            print(f"{PROG}: {len(written)} frame(s) at {args.fps:g} fps in {args.mp4}", flush=True)
    finally:  # not to be cut short by a second signal
        for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            signal.signal(s, signal.SIG_IGN)
        if browser is not None:
            browser.close()
        if viewer is not None:
            viewer.stop()


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    previous = {s: signal.signal(s, _raise_interrupted)
                for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    try:
        render(args)
        return 0
    except Failure as e:
        print(f"{PROG}: {e}", file=sys.stderr, flush=True)
        return 1
    except Interrupted as e:
        print(f"{PROG}: stopped by {signal.Signals(e.signum).name}", file=sys.stderr, flush=True)
        return 130
    except urllib.error.URLError as e:
        print(f"{PROG}: the viewer did not answer: {e.reason}", file=sys.stderr, flush=True)
        return 1
    except Exception as e:  # Selenium's WebDriverException and the like: their first line
        lines = str(getattr(e, "msg", None) or e).strip().splitlines()
        print(f"{PROG}: {type(e).__name__}: {lines[0] if lines else ''}", file=sys.stderr,
              flush=True)
        return 1
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)


if __name__ == "__main__":
    sys.exit(main())
