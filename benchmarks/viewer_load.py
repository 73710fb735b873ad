#!/usr/bin/python3
"""What a viewer costs the server: sim_server in lock-step on the built-in tongue
(scenes/tongue_sg_3n.yaml, dt 4 ms, every node published) driven by sequence_player through
steps of SG and GGp for --duration s of simulated time, in three set-ups taken in turn, A B C A B C:
  alone      the server and the player;
  viewer     the same with tongue_viewer watching the bus;
  page       the same with tongue_viewer and its page open in headless Chromium (the page
             draws with software WebGL, SwiftShader, on this machine's own cores).
Prints, per set-up, the median over the repeats of the server's steps per second (its run file's
timing_steps / timing_span_s: the steps alone, not the settling) and its ratio to `alone`, and
for `page` how many frames the page drew. Each run uses udpm port --port.

Usage: /usr/bin/python3 benchmarks/viewer_load.py [--duration 4] [--repeats 3] [--port 7998]
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import h5py

HERE = os.path.dirname(os.path.abspath(__file__))
PROJECT = os.path.normpath(os.path.join(HERE, ".."))
BUILD = os.environ.get("BUILD_DIR", os.path.join(PROJECT, "build"))
sys.path.insert(0, os.path.join(PROJECT, "scripts"))

from render_run import Browser, Page, Viewer  # noqa: E402

SIM_SERVER = os.path.join(BUILD, "sim_server", "apps", "sim_server")
SIM_COMMAND = os.path.join(BUILD, "sim_server", "apps", "sim_command")
PLAYER = os.path.join(BUILD, "controllers", "sequence_player", "sequence_player")
VIEWER = os.path.join(BUILD, "viewer", "tongue_viewer")
SCENE = os.path.join(PROJECT, "scenes", "tongue_sg_3n.yaml")
TIMEOUT_S = 300


def schedule(folder, duration):
    """SG and GGp switched on and off in turn, so that the tongue keeps moving."""
    path = os.path.join(folder, "schedule.yaml")
    entries = []
    t, on = 0.0, 0.25
    while t < duration:
        entries.append(f"  - {{muscle: SG, start: {t:.3f}, end: {min(t + on, duration):.3f}, force: 3.0}}")
        entries.append(f"  - {{muscle: GGp, start: {t + on:.3f}, end: {min(t + 2 * on, duration):.3f}, force: 4.0}}")
        t += 2 * on
    with open(path, "w") as f:
        f.write(f"duration: {duration}\nentries:\n" + "\n".join(entries) + "\n")
    return path


def one_run(setup, folder, sched, url, index):
    """Steps per second of the server in this set-up; frames the page drew (page only)."""
    output = os.path.join(folder, f"{setup}_{index}.h5")
    viewer = browser = page = None
    frames = None
    try:
        if setup in ("viewer", "page"):
            viewer = Viewer(VIEWER, ["--lcm-url", url, "--listen", "127.0.0.1:0"])
        if setup == "page":
            browser = Browser(1280, 720)
            page = Page(browser.driver)
            page.load(viewer.url)
        server = subprocess.Popen([SIM_SERVER, SCENE, "--lcm-url", url, "--output", output],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            if page:
                page.wait_ready()
            subprocess.run([PLAYER, "--schedule", sched, "--lcm-url", url], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=TIMEOUT_S)
            if page:
                frames = page.info()["framesDrawn"]
            subprocess.run([SIM_COMMAND, "shutdown", "--lcm-url", url], check=True)
            server.wait(TIMEOUT_S)
        finally:
            if server.poll() is None:
                server.kill()
                server.wait()
    finally:
        if browser:
            browser.close()
        if viewer:
            viewer.stop()
    with h5py.File(output, "r") as f:
        steps = float(f.attrs["timing_steps"])
        span = float(f.attrs["timing_span_s"])
    return steps / span, frames


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=4.0, help="simulated s per run")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--port", type=int, default=7998, help="udpm port of the runs")
    args = parser.parse_args()
    url = f"udpm://239.255.76.67:{args.port}?ttl=0&recv_buf_size=4194304"
    setups = ["alone", "viewer", "page"]
    rates = {s: [] for s in setups}
    frames = []
    with tempfile.TemporaryDirectory(prefix="viewer_load_") as folder:
        sched = schedule(folder, args.duration)
        for r in range(args.repeats):
            for s in setups:
                rate, drawn = one_run(s, folder, sched, url, r)
                rates[s].append(rate)
                if drawn is not None:
                    frames.append(drawn)
                print(f"  repeat {r + 1} {s:6s}: {rate:7.1f} steps/s"
                      + (f", page drew {drawn} frames" if drawn is not None else ""), flush=True)
    base = statistics.median(rates["alone"])
    steps = round(args.duration / 0.004)
    print(f"sim_server in lock-step, {steps} steps of 4 ms, medians of {args.repeats}:")
    for s in setups:
        m = statistics.median(rates[s])
        print(f"  {s:6s}: {m:7.1f} steps/s ({m * 0.004:.2f} x real time), {m / base:.3f} x alone")
    print(f"  the page drew {statistics.median(frames):.0f} of {steps} states (median)")


if __name__ == "__main__":
    main()
