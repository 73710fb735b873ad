#!/usr/bin/python3
"""Plot a run: landmark trajectories, muscle activations and forces, midsagittal shapes.

usage: plot_run.py RUN.h5 [--out DIR] [--times T [T ...]] [--csv]

Writes into DIR (default: the run file's folder), named after the run file RUN:
  RUN_landmarks.png  x and y (mm) of the landmarks tip, palatal dorsum, velar dorsum and root
                     (the first node of each of those node sets under /mesh/node_sets) against
                     time (ms), one row per landmark;
  RUN_muscles.png    activation (fraction of the maximum force) and force (activation x
                     /muscles/max_force, N) against time (ms) of every muscle that was ever
                     active, drawn as steps: frame k holds the level used during step k;
  RUN_shapes.png     the midsagittal outline at chosen times over the section at rest (light
                     grey): by default the first frame, three evenly spaced ones and the last;
                     --times T ... (s) picks the frames nearest to those times instead.
With --csv, the series plotted in the first two are written beside them as RUN_landmarks.csv
(time_ms, then <landmark>_x_mm, <landmark>_y_mm) and RUN_muscles.csv (time_ms, then
<muscle>_activation, <muscle>_force_N), every value with 17 significant digits.

A plot the run file lacks the data for (no landmark sets, no muscles or none ever active, no
midsagittal section) is skipped with a message saying why; the others are still drawn.

Exit status: 0 every plot drawn or skipped for lack of data; 1 the run file is missing or
unreadable, a --times value lies outside the run or DIR does not exist (nothing drawn), no plot
could be drawn, or one failed (the others are still drawn); 2 bad command line.
Run with Debian's Python (python3-h5py, python3-numpy, python3-matplotlib).
"""
import argparse
import csv
import os
import sys

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection

    from run_file import Run, RunError, boundary_edges, chain_edges, midsagittal_section
except ImportError as error:  # pragma: no cover - depends on the interpreter
    sys.exit("plot_run: %s (run with /usr/bin/python3 and python3-h5py, python3-numpy, "
             "python3-matplotlib installed)" % error)

PROG = "plot_run"
# The landmarks whose trajectories are plotted, front to back, with their labels.
TRAJECTORY_LANDMARKS = [("tip", "tip"), ("palatal_dorsum", "palatal dorsum"),
                        ("velar_dorsum", "velar dorsum"), ("root", "root")]
DEFAULT_SHAPES = 5  # frames drawn by default: the first, the last and evenly spaced between
REST_FILL = "#d9d9d9"


class Skipped(Exception):
    """A plot the run file has not the data for; the message says what is missing."""


def write_csv(path, header, columns):
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        for row in zip(*columns):
            writer.writerow(["%.17g" % v for v in row])


# ---------------------------------------------------------------------------------------------
# (a) Landmark trajectories


def landmark_series(run):
    """[(label, set name, node, positions [T x 3] in m)] of the trajectory landmarks present."""
    present = [(label, name, int(run.node_sets[name][0])) for name, label in TRAJECTORY_LANDMARKS
               if name in run.node_sets and len(run.node_sets[name])]
    if not present:
        raise Skipped("no landmark node set (%s) under /mesh/node_sets"
                      % ", ".join(name for name, _ in TRAJECTORY_LANDMARKS))
    paths = run.trajectories([node for _, _, node in present])
    return [(label, name, node, paths[:, i, :]) for i, (label, name, node) in enumerate(present)]


def plot_landmarks(run, out_png, out_csv):
    series = landmark_series(run)
    t_ms = run.time * 1e3
    fig, axes = plt.subplots(len(series), 2, figsize=(9.0, 1.9 * len(series) + 1.0), dpi=100,
                             sharex=True, squeeze=False)
    for row, (label, name, node, path) in enumerate(series):
        for col, (component, what) in enumerate([(0, "x"), (1, "y")]):
            ax = axes[row, col]
            ax.plot(t_ms, path[:, component] * 1e3, color="C%d" % row, linewidth=1.6)
            ax.set_ylabel("%s %s [mm]" % (label, what))
            ax.grid(True, color="#eeeeee", linewidth=0.6)
            ax.ticklabel_format(axis="y", useOffset=False)
    for col in range(2):
        axes[-1, col].set_xlabel("time [ms]")
    axes[0, 0].set_title("x (anterior)", fontsize=10)
    axes[0, 1].set_title("y (superior)", fontsize=10)
    fig.suptitle("%s \u2014 landmark trajectories" % os.path.basename(run.filename), fontsize=11)
    fig.tight_layout()
    fig.savefig(out_png)
    plt.close(fig)
    if out_csv:
        header, columns = ["time_ms"], [t_ms]
        for _, name, _, path in series:
            header += [name + "_x_mm", name + "_y_mm"]
            columns += [path[:, 0] * 1e3, path[:, 1] * 1e3]
        write_csv(out_csv, header, columns)
    return "landmarks %s" % ", ".join("%s (node %d)" % (name, node)
                                      for _, name, node, _ in series)


# ---------------------------------------------------------------------------------------------
# (b) Muscle activations and forces


def active_muscles(run):
    """[(name, activations [T], forces [T] in N)] of the muscles ever active."""
    if not run.muscle_names or run.activations is None:
        raise Skipped("no muscles in the run file (/muscles/names and /activations)")
    if run.max_force is None:
        raise Skipped("no /muscles/max_force (one per muscle) to turn activations into forces")
    ever = np.nonzero(run.activations.max(axis=0) > 0)[0]
    if len(ever) == 0:
        raise Skipped("no muscle was ever active (every activation is 0)")
    return [(run.muscle_names[i], run.activations[:, i], run.activations[:, i] * run.max_force[i])
            for i in ever]


def plot_muscles(run, out_png, out_csv):
    muscles = active_muscles(run)
    t_ms = run.time * 1e3
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9.0, 6.4), dpi=100, sharex=True)
    for i, (name, activation, force) in enumerate(muscles):
        # Earlier lines wider, so that one hidden under a later equal one (e.g. both halves of a
        # muscle at one level) still shows at its edges.
        style = dict(color="C%d" % (i % 10), linewidth=max(1.2, 3.0 - 0.6 * i),
                     drawstyle="steps-pre", linestyle="-" if i < 10 else "--")
        top.plot(t_ms, activation, label=name, **style)
        bottom.plot(t_ms, force, label=name, **style)
    top.set_ylabel("activation [fraction of max force]")
    bottom.set_ylabel("force [N]")
    bottom.set_xlabel("time [ms]")
    for ax in (top, bottom):
        ax.grid(True, color="#eeeeee", linewidth=0.6)
    top.set_ylim(bottom=0)
    bottom.set_ylim(bottom=0)
    top.legend(fontsize=8, ncol=min(4, len(muscles)), loc="best")
    fig.suptitle("%s \u2014 muscles ever active" % os.path.basename(run.filename), fontsize=11)
    fig.tight_layout()
    fig.savefig(out_png)
    plt.close(fig)
    if out_csv:
        header, columns = ["time_ms"], [t_ms]
        for name, activation, force in muscles:
            header += [name + "_activation", name + "_force_N"]
            columns += [activation, force]
        write_csv(out_csv, header, columns)
    return "muscles %s" % ", ".join(name for name, _, _ in muscles)


# ---------------------------------------------------------------------------------------------
# (c) Midsagittal shapes


def shape_frames(run, times):
    """Frames to draw: nearest to each of times (s), or the default spread."""
    if not times:
        count = min(DEFAULT_SHAPES, run.num_frames)
        return sorted(set(int(round(f)) for f in np.linspace(0, run.num_frames - 1, count)))
    first, last = run.time[0], run.time[-1]
    frames = []
    for t in times:
        # A time within half a frame spacing of the run's ends still picks the end frame.
        step = (last - first) / max(run.num_frames - 1, 1)
        if not first - step / 2 <= t <= last + step / 2:
            raise RunError("--times %g s is outside the run (%g s to %g s)" % (t, first, last))
        frames.append(int(np.argmin(np.abs(run.time - t))))
    return sorted(set(frames))


def plot_shapes(run, frames, out_png):
    try:
        faces, how = midsagittal_section(run, run.filename)
    except RunError as error:
        raise Skipped("no midsagittal section: %s" % error)
    loops = [f["loop"] for f in faces.values()]
    outline = chain_edges(boundary_edges(loops))
    rest_xy = run.rest[:, :2] * 1e3
    fig, ax = plt.subplots(figsize=(8.0, 6.4), dpi=100)
    ax.add_collection(PolyCollection([rest_xy[list(loop)] for loop in loops],
                                     facecolors=REST_FILL, edgecolors="#ffffff", linewidths=0.6,
                                     zorder=1, label="section at rest"))
    colors = plt.get_cmap("viridis")(np.linspace(0.0, 0.9, len(frames)))
    section_nodes = sorted(set().union(*map(set, loops)))
    points = [rest_xy[section_nodes]]
    for color, k in zip(colors, frames):
        xy = run.load(run.filename, k)[:, :2] * 1e3
        points.append(xy[section_nodes])
        ax.add_collection(LineCollection([xy[p] for p in outline], colors=[color],
                                         linewidths=1.6, zorder=3,
                                         label="t = %.1f ms" % (run.time[k] * 1e3)))
    points = np.vstack(points)
    lo, hi = points.min(axis=0), points.max(axis=0)
    pad = 0.08 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]  (anterior \u2192)")
    ax.set_ylabel("y [mm]  (superior \u2191)")
    ax.grid(True, color="#eeeeee", linewidth=0.6, zorder=0)
    ax.set_axisbelow(True)
    ax.legend(fontsize=8, loc="best")
    title = "%s \u2014 midsagittal outline at %d times" % (os.path.basename(run.filename),
                                                           len(frames))
    if how != "node set midsagittal":
        title += "\n(section: %s)" % how
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out_png)
    plt.close(fig)
    return "frames %s (t = %s ms)" % (", ".join(str(k) for k in frames),
                                      ", ".join("%.1f" % (run.time[k] * 1e3) for k in frames))


# ---------------------------------------------------------------------------------------------


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="plot_run.py",
        description="Plot a run file: landmark trajectories, muscle activations and forces, "
                    "midsagittal shapes at chosen times.")
    parser.add_argument("run", metavar="RUN.h5", help="HDF5 run file (sim_batch, sim_server)")
    parser.add_argument("--out", metavar="DIR",
                        help="folder for the pictures (default: the run file's folder)")
    parser.add_argument("--times", type=float, nargs="+", metavar="T",
                        help="times (s) of the midsagittal shapes; the nearest frames are drawn "
                             "(default: the first, the last and 3 evenly spaced frames)")
    parser.add_argument("--csv", action="store_true",
                        help="also write the plotted trajectories and muscle series as CSV")
    return parser.parse_args(argv)


def main(argv):
    args = parse_arguments(argv)
    try:
        run = Run(args.run)
        out_dir = args.out or os.path.dirname(os.path.abspath(args.run))
        if not os.path.isdir(out_dir):
            raise RunError("cannot write into %s: no such directory" % out_dir)
        stem = os.path.join(out_dir, os.path.splitext(os.path.basename(args.run))[0])
        frames = shape_frames(run, args.times)
    except RunError as error:
        print("%s: error: %s" % (PROG, error), file=sys.stderr)
        return 1
    except (OSError, KeyError, ValueError) as error:
        print("%s: error: %s: %s" % (PROG, args.run, error), file=sys.stderr)
        return 1

    plots = [
        ("landmark trajectories", stem + "_landmarks.png",
         lambda png: plot_landmarks(run, png, stem + "_landmarks.csv" if args.csv else None)),
        ("muscles", stem + "_muscles.png",
         lambda png: plot_muscles(run, png, stem + "_muscles.csv" if args.csv else None)),
        ("midsagittal shapes", stem + "_shapes.png", lambda png: plot_shapes(run, frames, png)),
    ]
    drawn, failed = 0, False
    for what, png, draw in plots:
        try:
            detail = draw(png)
            drawn += 1
            print("%s: wrote %s (%s)" % (PROG, png, detail))
        except Skipped as reason:
            print("%s: skipped the %s: %s" % (PROG, what, reason), file=sys.stderr)
        except (RunError, OSError, KeyError, ValueError) as error:
            print("%s: error: the %s: %s" % (PROG, what, error), file=sys.stderr)
            failed = True
    if drawn == 0:
        print("%s: error: %s has nothing to plot" % (PROG, args.run), file=sys.stderr)
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
