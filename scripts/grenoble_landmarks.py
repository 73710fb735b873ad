#!/usr/bin/env python3
"""Landmarks of an imported tongue mesh by a geometric rule (docs/your_tongue.md).

    python3 scripts/grenoble_landmarks.py NODE_FILE OUT_DIR [--axes xyz]

Reads an ANSYS NWRITE node file ("id x y z ...") and writes OUT_DIR/tip.txt,
palatal_dorsum.txt, velar_dorsum.txt and root.txt, each one node id. The rule, in the
mesh's coordinates with x anterior, y superior and z lateral (--axes names the file's columns
that play these roles, e.g. "zyx" when the file's z points forward):

  midsagittal nodes: |z - z_mid| <= 2 % of the width in z, z_mid the middle of the z range;
  tip:            the midsagittal node farthest forward (largest x);
  palatal_dorsum: the highest midsagittal node (largest y) in the front half of the x range;
  velar_dorsum:   the highest midsagittal node in the back half of the x range;
  root:           the midsagittal node farthest back (smallest x) in the middle half of the
                  y range.
"""
import argparse
import os
import sys


def read_nodes(path):
    nodes = {}
    with open(path, encoding="latin-1") as f:
        for number, line in enumerate(f, 1):
            fields = line.split()
            if not fields:
                continue
            try:
                values = [float(v) for v in fields[1:4]] + [0.0] * (4 - len(fields))
                nodes[int(fields[0])] = values[:3]
            except ValueError:
                sys.exit(f"{path}, line {number}: expected 'id x y z', got {line.strip()!r}")
    if not nodes:
        sys.exit(f"{path}: no nodes")
    return nodes


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("node_file")
    parser.add_argument("out_dir")
    parser.add_argument("--axes", default="xyz",
                        help="file columns playing anterior, superior, lateral (default xyz)")
    args = parser.parse_args()
    if sorted(args.axes) != ["x", "y", "z"]:
        sys.exit("--axes must be a permutation of xyz")
    column = ["xyz".index(a) for a in args.axes]
    nodes = {i: [p[column[0]], p[column[1]], p[column[2]]]
             for i, p in read_nodes(args.node_file).items()}
    lo = [min(p[c] for p in nodes.values()) for c in range(3)]
    hi = [max(p[c] for p in nodes.values()) for c in range(3)]
    z_mid = 0.5 * (lo[2] + hi[2])
    mid = {i: p for i, p in nodes.items() if abs(p[2] - z_mid) <= 0.02 * (hi[2] - lo[2])}
    if not mid:
        sys.exit("no midsagittal nodes: check --axes")
    x_mid = 0.5 * (lo[0] + hi[0])
    y_lo, y_hi = lo[1] + 0.25 * (hi[1] - lo[1]), lo[1] + 0.75 * (hi[1] - lo[1])

    def pick(name, candidates, key):
        if not candidates:
            sys.exit(f"no midsagittal node for {name}: check --axes")
        return max(candidates, key=key)

    front = [i for i, p in mid.items() if p[0] >= x_mid]
    back = [i for i, p in mid.items() if p[0] < x_mid]
    middle = [i for i, p in mid.items() if y_lo <= p[1] <= y_hi]
    chosen = {
        "tip": pick("tip", list(mid), lambda i: mid[i][0]),
        "palatal_dorsum": pick("palatal_dorsum", front, lambda i: mid[i][1]),
        "velar_dorsum": pick("velar_dorsum", back, lambda i: mid[i][1]),
        "root": pick("root", middle, lambda i: -mid[i][0]),
    }
    os.makedirs(args.out_dir, exist_ok=True)
    for name, node in chosen.items():
        with open(os.path.join(args.out_dir, name + ".txt"), "w") as f:
            f.write(f"{node}\n")
        print(f"{name}: node {node} at {nodes[node]}")


if __name__ == "__main__":
    main()
