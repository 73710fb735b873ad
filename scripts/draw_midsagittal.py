#!/usr/bin/python3
"""Draw a run's midsagittal section as Gerard et al. (2003), Figures 10-12.

usage: draw_midsagittal.py RUN.h5 [-o OUT.png] [--frame K] [--muscle NAME ...]
                           [--view3d OUT3D.png]

The picture: the tongue's midsagittal section at rest (/rest_positions) in light grey with its
element edges, the section's elements of the activated muscles in dark grey (at rest, as the
paper draws them), and the shape at the chosen frame as a solid black outline. Landmarks are
marked at rest (open) and at the frame (filled), joined by a line. When frame 0 (the settled
start) differs from the rest positions, its outline is drawn dashed. Axes in mm, x anterior to
the right, y up.

The section is the set of element faces whose 4 nodes all lie in /mesh/node_sets/midsagittal.
Without that node set, the elements crossing z = 0 are used, each drawn by its face nearest to
z = 0. A muscle whose elements never reach the section (a lateral one such as SG) is drawn by
the sagittal projection of its elements' faces nearest to z = 0, hatched.

The activated muscles: by default those with activation > 0 at the drawn frame (if none, at the
last frame, then at any frame); --muscle NAME (repeatable) overrides, where NAME is an element
set or a group (SG matches SG_left and SG_right).

--view3d OUT3D.png adds a 3D picture: the boundary surface at rest and at the frame, side by
side, the tongue translucent and the muscles' surfaces shaded dark inside it.

Run file (HDF5, SI units): /rest_positions [N x 3], /elements [E x 8] (hex8, bottom face
counter-clockwise then top face), /time [T], /positions [T x N x 3]; optional /mesh/node_sets/*,
/mesh/element_sets/*, /muscles/names, /muscles/max_force [N], /activations [T x M].

Exit status: 0 done; 1 missing or unreadable file, missing or malformed dataset, unknown muscle,
frame out of range; 2 bad command line.
Run with Debian's Python (python3-h5py, python3-numpy, python3-matplotlib).
"""
import argparse
import os
import sys

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    from run_file import (LANDMARKS, Run, RunError, area_centroid, boundary_edges,
                          boundary_faces, chain_edges, midsagittal_section, nearest_faces,
                          plane_section)
except ImportError as error:  # pragma: no cover - depends on the interpreter
    sys.exit("draw_midsagittal: %s (run with /usr/bin/python3 and python3-h5py, "
             "python3-numpy, python3-matplotlib installed)" % error)

PROG = "draw_midsagittal"
REST_FILL = "#d9d9d9"
REST_EDGE = "#ffffff"
MUSCLE_FILL = "#5a5a5a"
MUSCLE_EDGE = "#8c8c8c"
FINAL_LINE = "#000000"
SETTLED_LINE = "#7a7a7a"
REST_MARK = "#1f5fa8"
FINAL_MARK = "#c0392b"
OBSTACLE_LINE = "#1b6f3a"
CONTACT_MARK = "#e67e22"


# ---------------------------------------------------------------------------------------------
# Muscles


def resolve_muscles(run, requested, frame):
    """Returns (list of element-set names, note for the console)."""
    if requested:
        chosen = []
        for name in requested:
            matches = [s for s in run.element_sets
                       if s == name or (s.startswith(name + "_") and s != "all")]
            if not matches:
                available = sorted(s for s in run.element_sets if s != "all")
                raise RunError("no element set for muscle %s (available: %s)"
                               % (name, ", ".join(available) if available else "none"))
            for m in sorted(matches):
                if m not in chosen:
                    chosen.append(m)
        return chosen, None
    if run.activations is None or not run.muscle_names:
        return [], "the run has no /muscles/names or /activations: no muscle drawn"
    note = None
    active = np.nonzero(run.activations[frame] > 0)[0]
    if len(active) == 0:
        active = np.nonzero(run.activations[-1] > 0)[0]
        if len(active):
            note = "no muscle active at frame %d; drawing those active at the last frame" % frame
    if len(active) == 0:
        active = np.nonzero(run.activations.max(axis=0) > 0)[0]
        if len(active):
            note = "no muscle active at frame %d; drawing those active at some frame" % frame
    names = [run.muscle_names[i] for i in active]
    missing = [n for n in names if n not in run.element_sets]
    if missing:
        note = ((note + "; ") if note else "") + \
            "no element set for %s" % ", ".join(missing)
    return [n for n in names if n in run.element_sets], note


def muscle_summary(run, frame, drawn):
    """Text for the title: active muscles and their forces at the frame."""
    if run.activations is None or not run.muscle_names:
        return ", ".join(drawn) if drawn else "no muscle activation recorded"
    parts = []
    groups = {}
    order = []
    for i, name in enumerate(run.muscle_names):
        level = run.activations[frame, i]
        if level <= 0:
            continue
        group = name
        for side in ("_left", "_right"):
            if name.endswith(side):
                group = name[:-len(side)]
        force = level * run.max_force[i] if run.max_force is not None else None
        if group not in groups:
            groups[group] = []
            order.append(group)
        groups[group].append((name, level, force))
    for group in order:
        members = groups[group]
        if len(members) == 2 and all(m[0].startswith(group + "_") for m in members) \
                and abs(members[0][1] - members[1][1]) < 1e-12:
            # Both halves at the same level: one entry for the pair.
            level = members[0][1]
            if members[0][2] is not None:
                parts.append("%s %.3g N (%.0f%%, both sides)"
                             % (group, members[0][2] + members[1][2], 100 * level))
            else:
                parts.append("%s %.0f%% (both sides)" % (group, 100 * level))
            continue
        for name, level, force in members:
            if force is not None:
                parts.append("%s %.3g N (%.0f%%)" % (name, force, 100 * level))
            else:
                parts.append("%s %.0f%%" % (name, 100 * level))
    return ", ".join(parts) if parts else "no muscle active"


# ---------------------------------------------------------------------------------------------
# Drawing


def draw_section(run, filename, frame, muscles, out):
    faces, how = midsagittal_section(run, filename)
    loops = [f["loop"] for f in faces.values()]
    rest_xy = run.rest[:, :2] * 1e3
    final_xy = run.load(filename, frame)[:, :2] * 1e3
    start_xy = run.load(filename, 0)[:, :2] * 1e3

    muscle_elements = set()
    for m in muscles:
        muscle_elements.update(int(e) for e in run.element_sets[m])
    muscle_loops = [f["loop"] for f in faces.values() if f["elements"] & muscle_elements]
    section_elements = set().union(*(f["elements"] for f in faces.values()))
    # Muscles with no element in the section are projected; others only show their section.
    projected_muscles = [m for m in muscles
                         if not (set(int(e) for e in run.element_sets[m]) & section_elements)]
    projected_elements = sorted(set().union(*(set(int(e) for e in run.element_sets[m])
                                              for m in projected_muscles))) \
        if projected_muscles else []
    projected_loops = nearest_faces(run, projected_elements)

    fig, ax = plt.subplots(figsize=(8.0, 6.4), dpi=100)
    ax.add_collection(PolyCollection([rest_xy[list(l)] for l in loops], facecolors=REST_FILL,
                                     edgecolors=REST_EDGE, linewidths=0.7, zorder=1))
    if projected_loops:
        ax.add_collection(PolyCollection([rest_xy[list(l)] for l in projected_loops],
                                         facecolors=(0.35, 0.35, 0.35, 0.45),
                                         edgecolors=MUSCLE_FILL, linewidths=0.5,
                                         hatch="////", zorder=2))
    if muscle_loops:
        ax.add_collection(PolyCollection([rest_xy[list(l)] for l in muscle_loops],
                                         facecolors=MUSCLE_FILL, edgecolors=MUSCLE_EDGE,
                                         linewidths=0.6, zorder=3))
    outline = chain_edges(boundary_edges(loops))
    rest_outline = [rest_xy[p] for p in outline]
    ax.add_collection(LineCollection(rest_outline, colors="#9a9a9a", linewidths=0.8, zorder=4))
    settled = frame != 0 and np.abs(start_xy - rest_xy).max() > 1e-3  # > 1 um
    if settled:
        ax.add_collection(LineCollection([start_xy[p] for p in outline], colors=SETTLED_LINE,
                                         linewidths=1.0, linestyles=(0, (4, 3)), zorder=5))
    final_outline = [final_xy[p] for p in outline]
    ax.add_collection(LineCollection(final_outline, colors=FINAL_LINE, linewidths=2.0,
                                     capstyle="round", joinstyle="round", zorder=6))

    # Obstacles (their section by the plane z = 0) and the midsagittal nodes in contact.
    obstacle_segments = []
    for name, (vertices, triangles) in run.obstacles.items():
        segments = [seg[:, :2] * 1e3 for seg in plane_section(vertices, triangles)]
        if not segments:
            continue
        obstacle_segments.extend(segments)
        ax.add_collection(LineCollection(segments, colors=OBSTACLE_LINE, linewidths=2.2,
                                         capstyle="round", zorder=6))
        middle = segments[len(segments) // 2].mean(axis=0)
        ax.annotate(name.replace("_", " "), xy=middle, xytext=(4, 6), textcoords="offset points",
                    fontsize=7, color=OBSTACLE_LINE, zorder=10)
    in_contact = sorted(set(int(n) for n in run.contact_nodes(filename, frame))
                        & set(int(n) for n in run.node_sets.get("midsagittal", [])))
    if in_contact:
        ax.plot(final_xy[in_contact, 0], final_xy[in_contact, 1], marker="o", markersize=4.0,
                color=CONTACT_MARK, linestyle="none", zorder=9)

    # Landmarks.
    present = [(name, int(run.node_sets[name][0])) for name in LANDMARKS
               if name in run.node_sets and len(run.node_sets[name])
               and 0 <= run.node_sets[name][0] < len(run.rest)]
    section_nodes = sorted(set().union(*map(set, loops)))
    all_xy = np.vstack([rest_xy[section_nodes], final_xy[section_nodes]]
                       + ([np.vstack(obstacle_segments)] if obstacle_segments else []))
    center = area_centroid([rest_xy[list(l)] for l in loops])
    span = np.ptp(all_xy, axis=0).max()
    for name, n in present:
        r, f = rest_xy[n], final_xy[n]
        ax.plot([r[0], f[0]], [r[1], f[1]], color=FINAL_MARK, linewidth=1.0, zorder=7)
        ax.plot(*r, marker="o", markersize=5.5, markerfacecolor="white",
                markeredgecolor=REST_MARK, markeredgewidth=1.4, linestyle="none", zorder=8)
        ax.plot(*f, marker="o", markersize=4.5, color=FINAL_MARK, linestyle="none", zorder=9)
        # Label outward from the section's centre, beyond the outer of the two markers.
        anchor = r if np.linalg.norm(r - center) >= np.linalg.norm(f - center) else f
        d = anchor - center
        d = d / (np.linalg.norm(d) or 1.0)
        ha = "left" if d[0] > 0.35 else ("right" if d[0] < -0.35 else "center")
        va = "bottom" if d[1] > 0.35 else ("top" if d[1] < -0.35 else "center")
        ax.annotate(name.replace("_", " "), xy=anchor, xytext=tuple(9 * d),
                    textcoords="offset points", fontsize=8, color="#333333", ha=ha, va=va,
                    zorder=10,
                    bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8))

    lo = all_xy.min(axis=0)
    hi = all_xy.max(axis=0)
    pad = 0.12 * span
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]  (anterior \u2192)")
    ax.set_ylabel("y [mm]  (superior \u2191)")
    ax.grid(True, color="#eeeeee", linewidth=0.6, zorder=0)
    ax.set_axisbelow(True)

    t_ms = run.time[frame] * 1e3
    title = "%s \u2014 t = %.1f ms (frame %d/%d)" % (os.path.basename(filename), t_ms,
                                                           frame, run.num_frames - 1)
    subtitle = muscle_summary(run, frame, muscles)
    ax.set_title(title + "\n" + subtitle, fontsize=10)

    handles = [Patch(facecolor=REST_FILL, edgecolor="#9a9a9a", label="section at rest")]
    if muscle_loops:
        handles.append(Patch(facecolor=MUSCLE_FILL, edgecolor=MUSCLE_EDGE,
                             label="muscle: " + ", ".join(m for m in muscles
                                                          if m not in projected_muscles)))
    if projected_loops:
        handles.append(Patch(facecolor=(0.35, 0.35, 0.35, 0.45), edgecolor=MUSCLE_FILL,
                             hatch="////", label="projected (lateral): "
                             + ", ".join(projected_muscles)))
    if settled:
        handles.append(Line2D([], [], color=SETTLED_LINE, linewidth=1.0, linestyle=(0, (4, 3)),
                              label="frame 0 (settled)"))
    handles.append(Line2D([], [], color=FINAL_LINE, linewidth=2.0,
                          label="shape at t = %.1f ms" % t_ms))
    if obstacle_segments:
        handles.append(Line2D([], [], color=OBSTACLE_LINE, linewidth=2.2, label="obstacles"))
    if in_contact:
        handles.append(Line2D([], [], marker="o", markersize=4.0, color=CONTACT_MARK,
                              linestyle="none", label="in contact at t"))
    if present:
        handles.append(Line2D([], [], marker="o", markersize=5.5, markerfacecolor="white",
                              markeredgecolor=REST_MARK, markeredgewidth=1.4, linestyle="none",
                              label="landmark at rest"))
        handles.append(Line2D([], [], marker="o", markersize=4.5, color=FINAL_MARK,
                              linestyle="-", linewidth=1.0, label="landmark at t"))
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3,
              fontsize=8, frameon=False, handlelength=2.2)
    if how != "node set midsagittal":
        ax.text(0.01, 0.99, "section: " + how, transform=ax.transAxes, fontsize=7,
                va="top", color="#555555")
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
    return how


def draw_3d(run, filename, frame, muscles, out):
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    faces = boundary_faces(run.elements)
    muscle_elements = set()
    for m in muscles:
        muscle_elements.update(int(e) for e in run.element_sets[m])
    muscle_faces = boundary_faces(run.elements[sorted(muscle_elements)]) if muscle_elements \
        else []
    # Local element indices of muscle_faces refer to the sub-array; only loops are needed.
    positions = [("at rest", run.rest), ("t = %.1f ms" % (run.time[frame] * 1e3),
                                         run.load(filename, frame))]

    def to_plot(p):  # model (x anterior, y up, z left) -> plot (x, -z, y): y is vertical
        p = np.asarray(p) * 1e3
        return np.stack([p[..., 0], -p[..., 2], p[..., 1]], axis=-1)

    light = np.array([0.4, -0.5, 0.8])
    light /= np.linalg.norm(light)

    def shaded(polys, base, alpha):
        v = np.asarray(polys)
        n = np.cross(v[:, 2] - v[:, 0], v[:, 3] - v[:, 1])
        n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
        k = 0.55 + 0.45 * np.abs(n @ light)
        rgb = np.clip(np.outer(k, base), 0, 1)
        return np.hstack([rgb, np.full((len(v), 1), alpha)])

    all_pts = to_plot(np.vstack([p for _, p in positions]))
    lo, hi = all_pts.min(axis=0), all_pts.max(axis=0)
    pad = 0.03 * (hi - lo).max()
    lo, hi = lo - pad, hi + pad

    fig = plt.figure(figsize=(12.0, 5.6), dpi=100)
    for i, (label, pos) in enumerate(positions):
        ax = fig.add_subplot(1, 2, i + 1, projection="3d")
        xyz = to_plot(pos)
        surface = np.array([xyz[list(loop)] for loop, _ in faces])
        polys = [surface]
        colors = [shaded(surface, np.array([0.82, 0.82, 0.82]), 0.22 if muscle_faces else 1.0)]
        edges = [np.tile([[0.45, 0.45, 0.45, 0.35]], (len(surface), 1))]
        if muscle_faces:
            msurf = np.array([xyz[list(loop)] for loop, _ in muscle_faces])
            polys.append(msurf)
            colors.append(shaded(msurf, np.array([0.42, 0.42, 0.42]), 1.0))
            edges.append(np.tile([[0.15, 0.15, 0.15, 0.6]], (len(msurf), 1)))
        coll = Poly3DCollection(np.concatenate(polys), facecolors=np.vstack(colors),
                                edgecolors=np.vstack(edges), linewidths=0.3)
        ax.add_collection3d(coll)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(tuple(hi - lo), zoom=0.95)  # equal scale on the three axes
        ax.view_init(elev=18, azim=-62)
        ax.set_xlabel("x [mm] (anterior)", fontsize=8)
        ax.set_ylabel("-z [mm] (right)", fontsize=8)
        ax.set_zlabel("y [mm] (superior)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_title(label, fontsize=10)
    fig.suptitle("%s \u2014 %s" % (os.path.basename(filename),
                                    muscle_summary(run, frame, muscles)), fontsize=10)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="draw_midsagittal.py",
        description="Draw a run's midsagittal section (rest light grey, activated muscle dark "
                    "grey, final outline black) as Gerard et al. 2003, Figs. 10-12.")
    parser.add_argument("run", metavar="RUN.h5", help="HDF5 run file written by sim_batch")
    parser.add_argument("-o", "--output", metavar="OUT.png",
                        help="picture to write (default: RUN_midsagittal.png next to the run)")
    parser.add_argument("--frame", type=int, default=None, metavar="K",
                        help="frame to draw the shape of (default: the last; negative counts "
                             "from the end)")
    parser.add_argument("--muscle", action="append", default=[], metavar="NAME",
                        help="muscle to draw dark (repeatable; a group name such as SG matches "
                             "SG_left and SG_right); default: the active ones")
    parser.add_argument("--view3d", metavar="OUT3D.png",
                        help="also write a 3D view of the surface at rest and at the frame")
    return parser.parse_args(argv)


def main(argv):
    args = parse_arguments(argv)
    try:
        run = Run(args.run)
        frame = run.num_frames - 1 if args.frame is None else args.frame
        if not -run.num_frames <= frame < run.num_frames:
            raise RunError("--frame %d is out of range: the run has %d frames (0..%d)"
                           % (frame, run.num_frames, run.num_frames - 1))
        frame %= run.num_frames
        muscles, note = resolve_muscles(run, args.muscle, frame)
        if note:
            print("%s: %s" % (PROG, note), file=sys.stderr)
        out = args.output or os.path.splitext(args.run)[0] + "_midsagittal.png"
        for path in [out] + ([args.view3d] if args.view3d else []):
            folder = os.path.dirname(os.path.abspath(path))
            if not os.path.isdir(folder):
                raise RunError("cannot write %s: no such directory %s" % (path, folder))
        how = draw_section(run, args.run, frame, muscles, out)
        print("%s: wrote %s (frame %d, t = %.1f ms, section from %s, muscles: %s)"
              % (PROG, out, frame, run.time[frame] * 1e3, how,
                 ", ".join(muscles) if muscles else "none"))
        if args.view3d:
            draw_3d(run, args.run, frame, muscles, args.view3d)
            print("%s: wrote %s" % (PROG, args.view3d))
    except RunError as error:
        print("%s: error: %s" % (PROG, error), file=sys.stderr)
        return 1
    except (OSError, KeyError, ValueError) as error:
        print("%s: error: %s: %s" % (PROG, args.run, error), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
