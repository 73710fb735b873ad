#!/usr/bin/python3
"""A simulated electropalatogram (EPG) of a run with a palate obstacle.

usage: epg.py RUN.h5 [-o OUT.png] [--csv OUT.csv] [--palate NAME] [--frames K ...]

Speech scientists record tongue-palate contact with an artificial palate carrying electrodes;
the Reading EPG3 palate has 62 of them in 8 rows, 6 in the front row (behind the incisors) and 8
in each row behind it (Hardcastle, Gibbon & Jones 1991, "Visual display of tongue-palate contact:
electropalatography in the assessment and remediation of speech disorders", Br. J. Disord.
Commun. 26). This script lays that grid over the run's palate obstacle (default "hard_palate")
and switches an electrode on in a frame when a node the obstacles push on (/contact/node_force)
lies in its cell:

- rows: 8 equal bands of the palate's midsagittal length, from its front edge (the alveolar
  ridge) to its back edge, measured along its section by the plane z = 0;
- columns: within a row, equal bands of the palate's width at that place (6 in the front row,
  8 behind), from the subject's right (z < 0) to the left.

A node is placed on the palate by its nearest palate vertex, and counts only when that vertex is
within the palate's longest triangle edge of it (a node pushed by another obstacle, the velum,
lies farther from the palate). The picture shows the EPG frames
at the chosen frames (default: four frames spread over the run) and, below, the number of
electrodes on in each row against time; --csv writes every frame's 62 electrodes (1: on).
Run with Debian's Python (python3-h5py, python3-numpy, python3-matplotlib).
"""
import argparse
import os
import sys

try:
    import h5py
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from run_file import RunError, plane_section
except ImportError as error:  # pragma: no cover - depends on the interpreter
    sys.exit("epg: %s (run with /usr/bin/python3 and python3-h5py, python3-numpy, "
             "python3-matplotlib installed)" % error)

ROWS = 8
ROW_SIZES = [6] + [8] * 7  # Reading EPG3: 62 electrodes


def section_arc(vertices, triangles):
    """The palate's midsagittal section as an ordered polyline [P x 2] (x, y) from front to back
    (decreasing x), and its cumulative arc length."""
    segments = plane_section(vertices, triangles)
    if not segments:
        raise RunError("the palate does not cross the midsagittal plane z = 0")
    points = np.vstack([s[:, :2] for s in segments])
    # Order the section's points along the dominant direction of the section: its first
    # principal axis, oriented from the front (largest x) to the back.
    centre = points.mean(axis=0)
    _, _, axes = np.linalg.svd(points - centre)
    axis = axes[0] if axes[0][0] < 0 else -axes[0]
    order = np.argsort((points - centre) @ axis)
    ordered = points[order]
    keep = np.concatenate([[True], np.linalg.norm(np.diff(ordered, axis=0), axis=1) > 1e-9])
    ordered = ordered[keep]
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(ordered, axis=0), axis=1))])
    return ordered, arc


def palate_coordinates(vertices, triangles):
    """For each vertex: its position along the palate (0 front .. 1 back) and across it (-1
    right .. 1 left)."""
    polyline, arc = section_arc(vertices, triangles)
    # Along: the arc length of the nearest point of the section (in x, y).
    xy = vertices[:, :2]
    nearest = np.argmin(((xy[:, None, :] - polyline[None, :, :]) ** 2).sum(axis=-1), axis=1)
    along = arc[nearest] / arc[-1]
    # Across: z over the half-width of the vertices at about the same place along.
    across = np.zeros(len(vertices))
    bands = np.clip((along * ROWS * 4).astype(int), 0, ROWS * 4 - 1)
    for b in range(ROWS * 4):
        members = bands == b
        if members.any():
            half = np.abs(vertices[members, 2]).max()
            across[members] = vertices[members, 2] / (half if half > 0 else 1.0)
    return along, across


def electrode_of(along, across):
    """Electrode index (0..61, row by row from the front, right to left) of a palate point."""
    row = min(int(along * ROWS), ROWS - 1)
    size = ROW_SIZES[row]
    col = min(int((across + 1.0) / 2.0 * size), size - 1)
    return sum(ROW_SIZES[:row]) + max(col, 0)


def electrode_frames(h5, palate):
    """Electrodes on [T x 62] from the run's contact forces."""
    if "/obstacles/names" not in h5 or "/contact/node_force" not in h5:
        raise RunError("no obstacles or contact in the run file (a scene without obstacles)")
    names = [n.decode() if isinstance(n, bytes) else str(n) for n in h5["/obstacles/names"][()]]
    if palate not in names:
        raise RunError("no obstacle '%s' (the run has: %s)" % (palate, ", ".join(names)))
    vertices = np.asarray(h5["/obstacles/%s/vertices" % palate][()], float)
    triangles = np.asarray(h5["/obstacles/%s/triangles" % palate][()], np.int64)
    along, across = palate_coordinates(vertices, triangles)
    corners = vertices[triangles]
    reach = max(np.linalg.norm(corners[:, a] - corners[:, b], axis=1).max()
                for a, b in ((0, 1), (1, 2), (2, 0)))
    forces = h5["/contact/node_force"]
    positions = h5["/positions"]
    frames = np.zeros((forces.shape[0], sum(ROW_SIZES)), np.int8)
    for k in range(forces.shape[0]):
        touching = np.flatnonzero(np.abs(np.asarray(forces[k])).sum(axis=1) > 0.0)
        if touching.size == 0:
            continue
        x = np.asarray(positions[k])[touching]
        squared = ((x[:, None, :] - vertices[None, :, :]) ** 2).sum(axis=-1)
        nearest = np.argmin(squared, axis=1)
        for n, v in enumerate(nearest):
            if squared[n, v] <= reach * reach:
                frames[k, electrode_of(along[v], across[v])] = 1
    return frames


def draw(frames, times, chosen, title, out):
    fig = plt.figure(figsize=(2.2 * len(chosen) + 1.0, 6.0), dpi=100)
    grid = fig.add_gridspec(2, len(chosen), height_ratios=[1.3, 1.0])
    for i, k in enumerate(chosen):
        ax = fig.add_subplot(grid[0, i])
        for row, size in enumerate(ROW_SIZES):
            first = sum(ROW_SIZES[:row])
            xs = np.arange(size) - (size - 1) / 2.0
            on = frames[k, first:first + size] > 0
            ax.scatter(xs[~on], np.full((~on).sum(), -row), s=70, facecolors="white",
                       edgecolors="#555555", linewidths=0.8)
            ax.scatter(xs[on], np.full(on.sum(), -row), s=70, color="#111111")
        ax.set_xlim(-4.5, 4.5)
        ax.set_ylim(-ROWS + 0.4, 0.6)
        ax.set_aspect("equal")
        ax.axis("off")
        ax.set_title("t = %.0f ms\n%d on" % (times[k] * 1e3, int(frames[k].sum())), fontsize=9)
    ax = fig.add_subplot(grid[1, :])
    for row in range(ROWS):
        first = sum(ROW_SIZES[:row])
        ax.plot(times * 1e3, frames[:, first:first + ROW_SIZES[row]].sum(axis=1),
                label="row %d" % (row + 1), linewidth=1.2)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("electrodes on")
    ax.legend(ncol=4, fontsize=7, frameon=False)
    ax.grid(True, color="#eeeeee")
    fig.suptitle(title + " (front row at the top; the subject's right on the left)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def main(argv):
    parser = argparse.ArgumentParser(prog="epg.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("run", metavar="RUN.h5")
    parser.add_argument("-o", "--output", metavar="OUT.png",
                        help="picture (default: RUN_epg.png next to the run)")
    parser.add_argument("--csv", metavar="OUT.csv", help="electrodes of every frame, 1: on")
    parser.add_argument("--palate", default="hard_palate", help="the palate obstacle's name")
    parser.add_argument("--frames", type=int, nargs="+", metavar="K",
                        help="frames to draw (default: four spread over the run)")
    args = parser.parse_args(argv)
    try:
        if not os.path.isfile(args.run):
            raise RunError("no such file")
        with h5py.File(args.run, "r") as h5:
            frames = electrode_frames(h5, args.palate)
            times = np.asarray(h5["/time"][()], float)
    except (RunError, OSError, KeyError) as error:
        sys.exit("epg: %s: %s" % (args.run, error))
    count = len(frames)
    chosen = args.frames or sorted(set(int(round(f * (count - 1))) for f in (0.25, 0.5, 0.75, 1)))
    for k in chosen:
        if not 0 <= k < count:
            sys.exit("epg: %s: frame %d not in 0..%d" % (args.run, k, count - 1))
    out = args.output or os.path.splitext(args.run)[0] + "_epg.png"
    draw(frames, times, chosen, os.path.basename(args.run), out)
    if args.csv:
        header = ",".join(["time_s"] + ["r%dc%d" % (r + 1, c + 1) for r in range(ROWS)
                                         for c in range(ROW_SIZES[r])])
        np.savetxt(args.csv, np.column_stack([times, frames]), delimiter=",", header=header,
                   comments="", fmt=["%.6g"] + ["%d"] * frames.shape[1])
    print("epg: wrote %s (%d frames; electrodes on at the end: %d of 62)"
          % (out, count, int(frames[-1].sum())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
