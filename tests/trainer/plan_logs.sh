# Sourced by the smoother's tests (needs B and T): plan_logs NAME SCENE
# [hylo-scene options]: the scene's map and goal into $T/NAME.in.log, the
# planner node's answer into $T/NAME.plan.log, both into $T/NAME.all.log
# (LCM file:// logs: no network).
plan_logs() {
  local n=$1 scene=$2; shift 2
  "$B/bin/hylo-scene" "$scene" --goal "$@" --lcm-url "file://$T/$n.in.log?mode=w" &&
  "$B/bin/hylo-planner" --lcm-url "file://$T/$n.in.log?speed=0" --out-url "file://$T/$n.plan.log?mode=w" 2>/dev/null &&
  cat "$T/$n.in.log" "$T/$n.plan.log" > "$T/$n.all.log"
}
