#!/usr/bin/env bash
# Live UDP multicast between separate processes, only inside a network
# namespace this test creates (docs/deps.md): the planner node, the scene
# publisher, the listener, the Python client, and lcm-logger recording the
# session; then lcm-logplayer replays the recorded maps and goals into a new
# node, whose plans must equal the live ones. Where namespaces or the Python
# venv are unavailable the checks are reported as skipped, never as passed.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
NAMES=("node answers the scene publisher's goal over UDP"
       "listener prints the plan"
       "Python client gets its plan"
       "live plans equal the library's answers (plan_check on the lcm-logger log)"
       "logplayer replay into a new node gives identical plans")

tap_need_netns "${NAMES[@]}"
PY=.venv/bin/python
[ -x "$PY" ] && "$PY" -c "import lcm, yaml" 2>/dev/null || PY=""

# Everything below runs inside the namespace: its only interface is its own
# loopback, so no packet can leave this machine.
unshare --net env B="$B" T="$T" PY="$PY" bash -c '
set -u
. tests/node/wait.sh
trap "kill \$(jobs -p) 2>/dev/null" EXIT   # nothing outlives a failed wait
ip link set lo up && ip route add 224.0.0.0/4 dev lo || exit 3
URL="udpm://239.255.76.67:7667?ttl=0"
NODE=$B/test/node/hylo-planner-synthetic
lcm-logger --lcm-url="$URL" -f "$T/session.log" >/dev/null 2>&1 &
logger=$!
$B/bin/hylo-listen --lcm-url "$URL" --count 2 --timeout 60 > "$T/listen.txt" 2>&1 &
listen=$!
$NODE --lcm-url "$URL" 2> "$T/node.err" &
node=$!
wait_receivers 3 || exit 4   # the logger, the listener and the node
$B/bin/hylo-scene tests/node/synthetic.yaml --goal --request-id 1 --lcm-url "$URL"
# Request 2 only once request 1 is answered, so that it cannot supersede it.
wait_line "$T/listen.txt" "^plan 1 " || exit 4
if [ -n "$PY" ]; then
  $PY tools/hylo_client.py tests/node/synthetic.yaml --request-id 2 --lcm-url "$URL" \
    --timeout 20 > "$T/client.txt" 2>&1
  echo $? > "$T/client.rc"
else
  $B/bin/hylo-scene tests/node/synthetic.yaml --goal --request-id 2 --lcm-url "$URL"
fi
wait $listen; echo $? > "$T/listen.rc"
wait_plans $B/bin/hylo-listen "$T/session.log" 2 || exit 4
kill -INT $logger; wait $logger
kill -TERM $node; wait $node; echo $? > "$T/node.rc"

# Replay the recorded maps and goals (not the plans) into a fresh node.
lcm-logger --lcm-url="$URL" -f "$T/replay.log" >/dev/null 2>&1 &
logger=$!
$NODE --lcm-url "$URL" 2> "$T/node2.err" &
node=$!
wait_receivers 2 || exit 4   # the new logger and the new node
lcm-logplayer --lcm-url="$URL" -e "^HYLO_(MAP|GOAL)$" -s 4 "$T/session.log"
wait_plans $B/bin/hylo-listen "$T/replay.log" 2 || exit 4
kill -INT $logger; wait $logger
kill -TERM $node; wait $node
exit 0
'
rc=$?
if [ "$rc" -eq 3 ]; then
  for n in "${NAMES[@]}"; do tap_skip "$n" "namespace set-up failed (exit $rc)"; done
  tap_finish; exit
elif [ "$rc" -ne 0 ]; then
  for n in "${NAMES[@]}"; do tap_not_ok "$n" "a process never got ready (exit $rc): $(cat "$T"/*.err 2>/dev/null)"; done
  tap_finish; exit
fi

if grep -q "^request 1: ok" "$T/node.err" && [ "$(cat "$T/node.rc")" = 0 ]; then
  tap_ok "${NAMES[0]}"; else tap_not_ok "${NAMES[0]}" "$(cat "$T/node.err")"; fi
if [ "$(cat "$T/listen.rc")" = 0 ] && grep -q "^plan 1 (map 42, synthetic): ok" "$T/listen.txt"; then
  tap_ok "${NAMES[1]}"; else tap_not_ok "${NAMES[1]}" "$(cat "$T/listen.txt")"; fi
if [ -z "$PY" ]; then
  tap_skip "${NAMES[2]}" "no Python venv with lcm (make venv)"
elif [ "$(cat "$T/client.rc")" = 0 ] && grep -q "^plan 2 for map 42 (synthetic): ok" "$T/client.txt"; then
  tap_ok "${NAMES[2]}"; else tap_not_ok "${NAMES[2]}" "$(cat "$T/client.txt")"; fi
tap_check "${NAMES[3]}" "$B/test/node/plan_check" "$T/session.log" "$T/session.log"
tap_check "${NAMES[4]}" "$B/test/node/plan_check" "$T/session.log" "$T/replay.log"
tap_finish
