"""scripts/render_run.py: stills of the asked times (PNGs with a tongue in them), an MP4 when
ffmpeg is there, its errors, and no process left behind when it is stopped."""
import json
import os
import shutil
import signal
import subprocess

import pytest

from conftest import (RUN_TIMEOUT_S, START_TIMEOUT_S, assert_drawn, image_content, program,
                      project_path, wait_until, web_args)

SCRIPT = project_path("scripts", "render_run.py")
PYTHON = "/usr/bin/python3"


def render(*args, env=None):
    done = subprocess.run([PYTHON, SCRIPT, *map(str, args), "--viewer", program("TONGUE_VIEWER"),
                           *web_args()],
                          capture_output=True, text=True, stdin=subprocess.DEVNULL,
                          timeout=RUN_TIMEOUT_S, env=env)
    print(f"render_run.py {' '.join(map(str, args))}: exit {done.returncode}\n"
          f"stdout: {done.stdout}\nstderr: {done.stderr}")
    return done


def pngs(folder):
    return sorted(name for name in os.listdir(folder) if name.endswith(".png"))


def test_stills_of_the_asked_times_and_a_movie(runs, tmp_path):
    out = tmp_path / "frames"
    mp4 = tmp_path / "sg.mp4"
    ffmpeg = shutil.which("ffmpeg") is not None
    done = render(runs["sg"], "--times", 0, 0.06, 0.12, "--size", "640x360", "--out", out,
                  *(["--mp4", mp4, "--fps", 10] if ffmpeg else []))
    assert done.returncode == 0, done.stderr
    assert pngs(out) == ["frame_00000_t0.000s.png", "frame_00015_t0.060s.png",
                         "frame_00030_t0.120s.png"]
    pictures = []
    for name in pngs(out):
        with open(out / name, "rb") as f:
            png = f.read()
        width, height, _, _ = image_content(png)
        assert (width, height) == (640, 360), name
        assert_drawn(png, name)
        pictures.append(png)
    assert pictures[0] != pictures[2], "the tongue at 0 and at 0.12 s drawn alike"
    if not ffmpeg:
        pytest.skip("no ffmpeg on PATH: the stills are checked, not the movie")
    assert mp4.stat().st_size > 0
    if shutil.which("ffprobe"):
        probe = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames",
                                "-show_entries", "stream=width,height,nb_read_frames,codec_name",
                                "-of", "json", str(mp4)], capture_output=True, text=True,
                               timeout=START_TIMEOUT_S)
        assert probe.returncode == 0, probe.stderr
        stream = json.loads(probe.stdout)["streams"][0]
        assert stream["codec_name"] == "h264" and (stream["width"], stream["height"]) == (640, 360)
        assert int(stream["nb_read_frames"]) == 3, stream


def test_every_nth_frame_of_two_runs(runs, tmp_path):
    out = tmp_path / "frames"
    done = render(runs["sg"], "--reference", runs["ggp"], "--every", 10, "--view", "3d",
                  "--field", "displacement", "--camera", "oblique", "--size", "480x320",
                  "--out", out)
    assert done.returncode == 0, done.stderr
    assert [name[:11] for name in pngs(out)] == [f"frame_{k:05d}" for k in (0, 10, 20, 30)]
    for name in pngs(out):
        with open(out / name, "rb") as f:
            assert_drawn(f.read(), name)


def test_errors_are_one_line(runs, tmp_path):
    missing = tmp_path / "missing.h5"
    done = render(missing)
    assert done.returncode == 1 and done.stderr.strip() == f"render_run.py: no run file {missing}"
    notes = tmp_path / "notes.h5"
    notes.write_text("not HDF5\n")
    done = render(notes, "--out", tmp_path / "frames")
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 1 and len(lines) == 1, done.stderr
    assert "tongue_viewer exited with status" in lines[0] and str(notes) in lines[0], lines
    assert not (tmp_path / "frames").exists()
    # --mp4 without ffmpeg on PATH: status 1 (missing tool) before anything starts.
    done = render(runs["sg"], "--mp4", tmp_path / "x.mp4", "--out", tmp_path / "frames",
                  env={**os.environ, "PATH": str(tmp_path / "empty_path")})
    assert done.returncode == 1 and "ffmpeg" in done.stderr and len(done.stderr.splitlines()) == 1
    assert not (tmp_path / "frames").exists()


def descendants(pid):
    """The pids of pid's children, their children, ... (from /proc)."""
    found, todo = [], [pid]
    while todo:
        parent = todo.pop()
        try:
            with open(f"/proc/{parent}/task/{parent}/children") as f:
                children = [int(c) for c in f.read().split()]
        except OSError:
            children = []
        found += children
        todo += children
    return found


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def program_name(pid):
    try:
        with open(f"/proc/{pid}/comm") as f:
            return f.read().strip()
    except OSError:
        return ""


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_stopped_midway_it_leaves_no_process(runs, tmp_path, signum):
    script = subprocess.Popen([PYTHON, SCRIPT, runs["sg"], "--out", tmp_path / "frames",
                               "--size", "320x240", "--viewer", program("TONGUE_VIEWER"),
                               *web_args()],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              stdin=subprocess.DEVNULL)
    seen = set()
    try:
        # Midway: the viewer and the browser both up, the first frames written.
        def started():
            seen.update(descendants(script.pid))
            names = {program_name(pid) for pid in seen}
            frames = os.path.isdir(tmp_path / "frames") and pngs(tmp_path / "frames")
            return script.poll() is not None or (
                "tongue_viewer" in names and "chromedriver" in names and frames)
        wait_until(started, RUN_TIMEOUT_S, "render_run.py to start the viewer and the browser")
        assert script.poll() is None, "render_run.py ended before it could be stopped"
        seen.update(descendants(script.pid))
        script.send_signal(signum)
        _, stderr = script.communicate(timeout=START_TIMEOUT_S)
        assert script.returncode == 130, stderr
        assert f"stopped by {signal.Signals(signum).name}" in stderr
        wait_until(lambda: not any(alive(pid) for pid in seen), START_TIMEOUT_S,
                   "the viewer and the browser to be gone")
    finally:
        if script.poll() is None:
            script.kill()
            script.communicate()
        for pid in seen:  # only what the script started, should the test fail
            if alive(pid):
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
