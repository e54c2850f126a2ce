#!/usr/bin/env bash
# A mode added in one place (tests/toymode/toy_mode.h: its value, its record,
# its trainer model) flows through the whole pipeline: the toy build's
# trainer reads a robot file with mode "toy", generates a few training rows,
# fits and exports a model header that names HYLO_MODE_TOY;
# tools/gen-model-registry registers it for robot "toy" without a list of
# modes; the planner node's registry gives the robot that mode and model;
# and the onboard library plans with it (tests/toymode/toy_plan.c).
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
TR=$B/toy/bin/trainer
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
mkdir -p "$T/params" "$T/models"
cat > "$T/params/toy.yaml" <<'YAML'
robot: toy
g: 9.81
modes:
  toy:
    params: {rho: 0.1}
    sampling: {max_distance_m: 2.0, speed_min_mps: -1.0, speed_max_mps: 1.0}
YAML

# Training: 60 rows, the fit and the export.
if HYLO_PARAMS_DIR="$T/params" "$TR" --robot toy --mode toy --samples 60 --jobs 2 --out "$T/data" \
     --models-dir "$T/models" > "$T/train.log" 2>&1; then
  tap_ok "the toy trainer trains robot toy's mode toy (gen, fit, export)"; else
  tap_not_ok "the toy trainer trains robot toy's mode toy (gen, fit, export)" "$(tail -5 "$T/train.log")"; fi
rows=$(($(wc -l < "$T/data/toy.csv" 2>/dev/null || echo 1) - 1))
conv=$(awk -F, 'NR > 1 && $12 == 1' "$T/data/toy.csv" 2>/dev/null | wc -l)
if [ "$rows" -eq 60 ] && [ "$conv" -ge 30 ] && head -1 "$T/data/toy.csv" | grep -q '^index,f0,f1,f2,f3,x1_0,x1_1,x2_0,x2_1,cost_j'; then
  tap_ok "the dataset has 60 rows of 4 relative coordinates and 2 + 2 coordinates ($conv converged)"; else
  tap_not_ok "the dataset has 60 rows of 4 relative coordinates and 2 + 2 coordinates" "rows $rows, converged $conv"; fi
H=$T/models/toy_toy.h
if grep -q '^#define HYLO_MODEL_TOY_TOY_MODE HYLO_MODE_TOY$' "$H" 2>/dev/null &&
   grep -q '^#define HYLO_MODEL_TOY_TOY_N_FEATURES 5$' "$H"; then
  tap_ok "the exported header names HYLO_MODE_TOY and the phase layout's 5 features"; else
  tap_not_ok "the exported header names HYLO_MODE_TOY and the phase layout's 5 features" "$(grep '^#define' "$H" 2>&1 | head -5)"; fi

# Registry: the generator knows no list of modes.
if tools/gen-model-registry "$T/registry.c" --params "$T/params" "$T/models" > "$T/gen.log" 2>&1 &&
   grep -q '{ &hylo_model_toy_toy, .*, "toy", HYLO_MODEL_TOY_TOY_MODE, -1, -1 },' "$T/registry.c"; then
  tap_ok "gen-model-registry registers toy_toy.h for robot toy"; else
  tap_not_ok "gen-model-registry registers toy_toy.h for robot toy" "$(cat "$T/gen.log" "$T/registry.c" 2>&1 | tail -8)"; fi

# Planning: the registry's robot toy, a plan on the phase plane.
if gcc -std=c99 -DHYLO_EXTRA_MODES_H='"toymode/toy_mode.h"' -Itests -Ionboard/include -Ionboard -I"$T/models" \
     tests/toymode/toy_plan.c "$T/registry.c" onboard/node/registry.c "$B/toy/lib/libhylo.a" -lm \
     -o "$T/toy_plan" > "$T/cc.log" 2>&1; then
  tap_ok "a planner program compiles with the toy registry"; else
  tap_not_ok "a planner program compiles with the toy registry" "$(tail -8 "$T/cc.log")"; fi
if "$T/toy_plan" > "$T/plan.txt" 2>&1 &&
   grep -q '^registry: robot toy, mode toy (6), model toy_toy, 5 features$' "$T/plan.txt" &&
   grep -q '^plan: ' "$T/plan.txt" && ! grep '^  ' "$T/plan.txt" | grep -qv '^  toy '; then
  tap_ok "the registry gives robot toy its mode and model, and the planner plans in mode toy"; else
  tap_not_ok "the registry gives robot toy its mode and model, and the planner plans in mode toy" "$(head -8 "$T/plan.txt")"; fi
sed 's/^/# /' "$T/plan.txt" | head -12
tap_finish
