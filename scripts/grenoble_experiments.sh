#!/usr/bin/env bash
# The paper's three experiments (SG 3 N, GGp 4 N, SL 1 N; Gerard et al. 2003 sec. IV.2) on your
# own tongue from the Grenoble files (docs/your_tongue.md):
#   bash scripts/grenoble_experiments.sh DIR
# DIR holds tongue.node, tongue.elem, CreateMuscles.mac, Fibers.mac, MuscleMaxForce.txt,
# jaw_nodes.txt, hyoid_nodes.txt and external_points.txt (the fibres' points on bone; an empty
# one, with a comment, is written if missing). The scenes/templates/grenoble link is made to point
# at it, the landmarks are chosen by scripts/grenoble_landmarks.py unless DIR/landmarks/ exists,
# and each experiment writes logs/grenoble_<name>.h5 and prints its landmarks' displacements.
set -euo pipefail
if [[ $# -ne 1 ]]; then
  echo "usage: bash scripts/grenoble_experiments.sh DIR" >&2
  exit 2
fi
dir=$(cd "$1" && pwd)
cd "$(dirname "$0")/.."
link=scenes/templates/grenoble
if [[ -e $link && ! -L $link ]]; then
  echo "grenoble_experiments: $link exists and is not a link; move it away" >&2
  exit 1
fi
ln -sfn "$dir" "$link"
if [[ ! -e $dir/external_points.txt ]]; then
  echo "grenoble_experiments: no $dir/external_points.txt: writing an empty one (no fibre ends on bone)"
  echo "# id x y z [m]: points of Fibers.mac outside the mesh (bone); none" >"$dir/external_points.txt"
fi
if [[ ! -d $dir/landmarks ]]; then
  /usr/bin/python3 scripts/grenoble_landmarks.py "$dir/tongue.node" "$dir/landmarks"
fi
for experiment in sg_3n ggp_4n sl_1n; do
  echo "== $experiment"
  build/sim_server/apps/sim_batch "scenes/templates/grenoble_$experiment.yaml" --quiet
done
