#!/usr/bin/env bash
# make demo: plans the default scenes through the planner node's LCM path
# (file:// logs: no multicast route needed) with the committed models, and
# prints each plan. Scenes whose robot has no committed model are reported
# with the command that trains one.
set -u
cd "$(dirname "$0")/.."
B=${BUILD:-build}
D=$B/demo
rm -rf "$D" && mkdir -p "$D"
status=0
for scene in scenes/di.yaml scenes/river_crossing.yaml; do
  name=$(basename "$scene" .yaml)
  echo "== $scene"
  "$B/bin/hylo-scene" "$scene" --check | sed 's/^/   /'
  "$B/bin/hylo-scene" "$scene" --goal --lcm-url "file://$D/$name.in.log?mode=w" || { status=1; continue; }
  "$B/bin/hylo-planner" --lcm-url "file://$D/$name.in.log?speed=0" \
    --out-url "file://$D/$name.plan.log?mode=w" 2> "$D/$name.node.log" || status=1
  sed 's/^/   node: /' "$D/$name.node.log"
  "$B/bin/hylo-listen" --lcm-url "file://$D/$name.plan.log?speed=0" --waypoints | sed 's/^/   /'
  if grep -q "no model" "$D/$name.node.log"; then
    robot=$(sed -n 's/^robot: *//p' "$scene")
    echo "   (no committed model for $robot yet: train with"
    echo "    build/bin/trainer --robot $robot --mode ground, and --mode marine/flight)"
  fi
done
echo "logs of this run: $D/"
exit $status
