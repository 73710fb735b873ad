#!/usr/bin/env bash
# Reference runs of the built-in tongue (dt 0.1 ms, Newton tolerances far below
# any working setting) and the nodal error of the default settings (dt 4 ms) against them:
#   1. SG 3 N for 120 ms, then 200 ms of relaxation (sim_batch, scenes/tongue_sg_3n_relax*.yaml);
#   2. /ai/ in closed loop with ep_controller (run_experiment, experiments/ai.yaml and
#      experiments/reference/ai_reference.yaml).
# References go to logs/reference/. Run from anywhere after building into build/:
#   bash scripts/reference_runs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
compare() { /usr/bin/python3 scripts/compare_runs.py "$1" "$2"; }

mkdir -p logs/reference
echo "== SG 3 N + relaxation: reference (dt 0.1 ms), then default settings (dt 4 ms)"
"$build/sim_server/apps/sim_batch" scenes/tongue_sg_3n_relax_reference.yaml --quiet
"$build/sim_server/apps/sim_batch" scenes/tongue_sg_3n_relax.yaml --quiet
compare logs/tongue_sg_3n_relax.h5 logs/reference/tongue_sg_3n_relax_reference.h5

echo "== /ai/ with ep_controller: reference (dt 0.1 ms), then default settings (dt 4 ms)"
"$build/experiments/run_experiment" experiments/reference/ai_reference.yaml --logs logs/reference \
  --no-plots --quiet | tail -n 12
"$build/experiments/run_experiment" experiments/ai.yaml --no-plots --quiet | tail -n 12
compare logs/ai-latest/run.h5 logs/reference/ai_reference-latest/run.h5
