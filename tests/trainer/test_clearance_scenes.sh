#!/usr/bin/env bash
# Published trajectories keep the robot's body clear (docs/smoothing.md,
# "Clearance"), checked from outside the trainer: Ambot's committed scenes
# planned by the node and smoothed by hylo-smooth, then a walk written here
# from the definition (tools/clearance_walk.py: the map_t and traj_t as
# published, every sample and points 0.02 m apart between them, Ambot's body
# from its robot file) finds every point in its mode's cells and at least
# body + margin from every hazard, and traj_t says safe. island_crossing's
# shore is a staircase where the smoother used to leave a ground phase 0.13 m
# into the water; the walk reports that trajectory as outside (checked on a
# smoothing without corridors).
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
. tests/trainer/plan_logs.sh
SCENES=(island_crossing river_crossing)
PY=.venv/bin/python
if ! { [ -x "$PY" ] && "$PY" -c "import lcm, yaml" 2>/dev/null; }; then
  for n in "${SCENES[@]}" no_corridors; do tap_skip "$n" "no .venv with lcm and PyYAML (make venv)"; done
  tap_finish; exit
fi
walk() { "$PY" tools/clearance_walk.py --map-log "$T/$1.in.log" --traj-log "$T/$1.$2.traj.log" --robot-file trainer/params/ambot.yaml; }

# One plan per scene (the alternatives are smoothed by the same code, and
# three would triple the time; test_alternatives.sh covers choosing one).
for n in "${SCENES[@]}"; do
  plan_logs "$n" "scenes/$n.yaml" --alternatives 1 &&
  "$B/bin/hylo-smooth" --once --quiet --lcm-url "file://$T/$n.all.log?speed=0" --out-url "file://$T/$n.on.traj.log?mode=w"
  out=$(walk "$n" on 2>&1); rc=$?
  if [ "$rc" -eq 0 ]; then tap_ok "$n: published trajectory inside its domain with body + margin ($out)"
  else tap_not_ok "$n: published trajectory inside its domain with body + margin" "$out"; fi
done
# The walk can fail: the island without corridors leaves the domain.
"$B/bin/hylo-smooth" --once --quiet --no-corridors --lcm-url "file://$T/island_crossing.all.log?speed=0" \
  --out-url "file://$T/island_crossing.off.traj.log?mode=w"
out=$(walk island_crossing off 2>&1); rc=$?
if [ "$rc" -eq 1 ] && [ "${out#*outside}" != "$out" ]; then tap_ok "no_corridors: the walk finds the island's trajectory outside ($out)"
else tap_not_ok "no_corridors: the walk finds the island's trajectory outside" "exit $rc: $out"; fi
tap_finish
