#!/usr/bin/env bash
# make demo: plans the default scenes through the planner node's LCM path with
# the committed models, prints each plan, smooths it (hylo-smooth) and draws
# both into out/<scene>.png.
#   make demo                 file:// logs: no multicast route needed
#   make demo LCM_URL=URL     a live bus: starts hylo-planner and hylo-smooth on
#                             URL, publishes each scene, records the bus with
#                             lcm-logger and renders from the recording
# Scenes whose robot has no committed model are reported with the command
# that trains one.
set -u
cd "$(dirname "$0")/.."
B=${BUILD:-build}
D=$B/demo
URL=${LCM_URL:-}
rm -rf "$D" && mkdir -p "$D" out
status=0

if [ -n "$URL" ]; then
  echo "live bus: $URL"
  "$B/bin/hylo-planner" --lcm-url "$URL" 2> "$D/planner.log" &
  planner=$!
  "$B/bin/hylo-smooth" --lcm-url "$URL" > "$D/smoother.log" 2>&1 &
  smoother=$!
  trap 'kill $planner $smoother 2>/dev/null' EXIT
  sleep 0.5
fi

for scene in scenes/di.yaml scenes/river_crossing.yaml; do
  name=$(basename "$scene" .yaml)
  echo "== $scene"
  "$B/bin/hylo-scene" "$scene" --check | sed 's/^/   /'
  if [ -n "$URL" ]; then
    # Record the bus until the plan and its trajectory have gone by.
    lcm-logger --lcm-url="$URL" -f "$D/$name.live.log" > /dev/null 2>&1 &
    logger=$!
    "$B/bin/hylo-listen" --lcm-url "$URL" --count 2 --timeout 300 > "$D/$name.listen.txt" &
    listener=$!
    sleep 0.3
    "$B/bin/hylo-scene" "$scene" --goal --lcm-url "$URL" || status=1
    wait $listener || status=1
    sleep 0.2
    kill -INT $logger; wait $logger
    sed 's/^/   /' "$D/$name.listen.txt"
    logs=(--log "$D/$name.live.log")
  else
    "$B/bin/hylo-scene" "$scene" --goal --lcm-url "file://$D/$name.in.log?mode=w" || { status=1; continue; }
    "$B/bin/hylo-planner" --lcm-url "file://$D/$name.in.log?speed=0" \
      --out-url "file://$D/$name.plan.log?mode=w" 2> "$D/$name.node.log" || status=1
    sed 's/^/   node: /' "$D/$name.node.log"
    "$B/bin/hylo-listen" --lcm-url "file://$D/$name.plan.log?speed=0" --waypoints | sed 's/^/   /'
    # Smoothing: one multi-phase optimization over the plan's mode sequence.
    cat "$D/$name.in.log" "$D/$name.plan.log" > "$D/$name.planned.log"
    "$B/bin/hylo-smooth" --lcm-url "file://$D/$name.planned.log?speed=0" \
      --out-url "file://$D/$name.traj.log?mode=w" 2>&1 | sed 's/^/   smoothed: /'
    logs=(--log "$D/$name.in.log" --log "$D/$name.plan.log" --log "$D/$name.traj.log")
  fi
  "$B/bin/hylo-render" --quiet "${logs[@]}" --out "out/$name.png" 2>/dev/null &&
    echo "   picture: out/$name.png"
  if grep -qs "no model" "$D/$name.node.log" "$D/planner.log"; then
    robot=$(sed -n 's/^robot: *//p' "$scene")
    echo "   (no committed model for $robot yet: train with"
    echo "    build/bin/trainer --robot $robot --mode ground, and --mode marine/flight)"
  fi
done
[ -n "$URL" ] && sed 's/^/smoother: /' "$D/smoother.log"
echo "logs of this run: $D/"
exit $status
