#!/usr/bin/python3
"""Draws the real-time factor against the RMS nodal error of rtf_error_benchmark's CSV.

Usage: /usr/bin/python3 scripts/plot_rtf_error.py logs/rtf_error.csv logs/rtf_error.png
           [--closed-loop logs/closed_loop.csv] [--reduced logs/reduced.csv]

Log-log axes; one marker per setting: colour by time step, shape by solver policy and material,
hollow for 2 threads. The dashed lines are the targets: real time (RTF = 1) and 0.1 mm RMS.
With --closed-loop, closed_loop_benchmark's rows that have an error against their reference are
drawn too, as stars labelled with the scenario (at the scene's dt, sim_server and a controller
process in lock-step; their RTF is the closed loop's, their error against their own reference
run).
With --reduced, reduced_benchmark's rows are drawn as plus signs labelled with their modes and
sampled elements: the reduced model's RTF on its held-out runs, its RMS error against the full
model at the same dt (not against the reference), over all runs (filled) and the worst run in
which the full model's material stays strongly elliptic (hollow).
"""
import argparse
import csv
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path, needed):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{path}: no rows")
    missing = needed - set(rows[0])
    if missing:
        raise SystemExit(f"{path}: missing columns {sorted(missing)}")
    return rows


def draw_closed_loop(ax, path):
    """The closed-loop rows with an error (one thread) as labelled stars."""
    drawn = False
    for r in read_rows(path, {"scenario", "threads", "rtf", "rms_mm"}):
        rms = float(r["rms_mm"])
        if r["threads"] != "1" or math.isnan(rms):
            continue
        rtf = float(r["rtf"])
        ax.scatter(max(rms, 1e-6), rtf, marker="*", s=140, color="crimson",
                   label=None if drawn else "closed loop (lock-step, the scene's dt)")
        ax.annotate(r["scenario"], (rms, rtf), textcoords="offset points", xytext=(-7, 6),
                    ha="right", fontsize=7, color="crimson")
        drawn = True


def draw_reduced(ax, path):
    """reduced_benchmark's rows: one per basis."""
    for i, r in enumerate(read_rows(path, {"modes", "sampled", "rtf", "rms_mm",
                                           "stable_worst_rms_mm"})):
        rtf = float(r["rtf"])
        ax.scatter(float(r["rms_mm"]), rtf, marker="P", s=90, color="darkorange",
                   label=None if i else "reduced model, all held-out runs (error against the "
                   "full model)")
        ax.scatter(max(float(r["stable_worst_rms_mm"]), 1e-6), rtf, marker="P", s=90,
                   facecolors="none", edgecolors="darkorange",
                   label=None if i else "reduced model, worst run where the material is "
                   "elliptic")
        ax.annotate(f'{r["modes"]} modes, {r["sampled"]} el.', (float(r["rms_mm"]), rtf),
                    textcoords="offset points", xytext=(-6, -12), ha="right", fontsize=7,
                    color="darkorange")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv")
    parser.add_argument("png")
    parser.add_argument("--closed-loop", help="closed_loop_benchmark's CSV")
    parser.add_argument("--reduced", help="reduced_benchmark's CSV")
    args = parser.parse_args()
    rows = read_rows(args.csv,
                     {"dt_ms", "tolerance", "newton", "material", "threads", "rtf", "rms_mm"})
    dts = sorted({float(r["dt_ms"]) for r in rows})
    colours = plt.cm.viridis([i / max(1, len(dts) - 1) for i in range(len(dts))])
    colour_of = dict(zip(dts, colours))
    fig, ax = plt.subplots(figsize=(11, 5.5))
    seen = set()
    for r in rows:
        rms = max(float(r["rms_mm"]), 1e-6)  # mm; a zero error cannot sit on a log axis
        rtf = float(r["rtf"])
        dt = float(r["dt_ms"])
        if r["material"] != "mooney_rivlin5":
            marker, kind = ("s" if r["material"] == "neo_hookean" else "D"), r["material"]
        elif r["newton"] == "full":
            marker, kind = "^", "full Newton"
        else:
            marker, kind = "o", "factor reuse"
        hollow = r["threads"] == "2"
        key = (kind, marker, hollow)
        if key not in seen:  # one grey legend entry per kind of marker
            seen.add(key)
            ax.scatter([], [], marker=marker, s=60, label=kind + (", 2 threads" if hollow else ""),
                       facecolors="none" if hollow else "grey", edgecolors="grey")
        ax.scatter(rms, rtf, marker=marker, s=60,
                   facecolors="none" if hollow else colour_of[dt],
                   edgecolors=colour_of[dt], linewidths=1.5)
        if r["tolerance"] != "default":
            ax.annotate(r["tolerance"], (rms, rtf), textcoords="offset points", xytext=(5, 4),
                        fontsize=7)
    for dt in dts:
        ax.scatter([], [], color=colour_of[dt], marker="o", label=f"dt {dt:g} ms")
    if args.closed_loop:
        draw_closed_loop(ax, args.closed_loop)
    if args.reduced:
        draw_reduced(ax, args.reduced)
    ax.axhline(1.0, color="grey", linestyle="--", linewidth=1)
    ax.axvline(0.1, color="grey", linestyle="--", linewidth=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("RMS nodal error against the reference [mm]")
    ax.set_ylabel("real-time factor [simulated s / wall s]")
    title = "Default tongue, SG 3 N 120 ms + 200 ms relaxation (mooney_rivlin5 reference)"
    if args.closed_loop:
        title += "\nand closed loops (stars), each against its own reference run"
    if args.reduced:
        title += "\nand the reduced model (plus signs) against the full model at the same dt"
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside the points
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)


if __name__ == "__main__":
    main()
