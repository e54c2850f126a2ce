#!/usr/bin/env bash
# make pictures: plans every scene through the planner node (file:// logs)
# with the committed models, smooths the plan (hylo-smooth) and draws both
# with hylo-render into docs/pictures/<scene>.png, and records the scene,
# robot file and models each was made from (tools/provenance). A scene whose
# robot has no committed model yet is drawn without a path (the title says why).
# Arguments: scene files to draw alone (default: every scenes/*.yaml), e.g.
# after one robot's models changed.
set -u
cd "$(dirname "$0")/.."
B=${BUILD:-build}
OUT=docs/pictures
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
mkdir -p "$OUT"
status=0
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/*.yaml)
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .yaml)
  "$B/bin/hylo-scene" "$scene" --goal --lcm-url "file://$W/$name.in.log?mode=w" || { status=1; continue; }
  "$B/bin/hylo-planner" --lcm-url "file://$W/$name.in.log?speed=0" \
    --out-url "file://$W/$name.plan.log?mode=w" 2> "$W/$name.node.log" || status=1
  cat "$W/$name.in.log" "$W/$name.plan.log" > "$W/$name.planned.log"
  "$B/bin/hylo-smooth" --quiet --lcm-url "file://$W/$name.planned.log?speed=0" \
    --out-url "file://$W/$name.traj.log?mode=w" 2> "$W/$name.smooth.log" || status=1
  "$B/bin/hylo-render" --log "$W/$name.in.log" --log "$W/$name.plan.log" --log "$W/$name.traj.log" \
    --camera "$("$B/bin/hylo-scene" "$scene" --print-camera)" --out "$OUT/$name.png" &&
    tools/provenance record "$OUT/$name.png" || status=1
done
exit $status
