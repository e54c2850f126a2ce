#!/usr/bin/env bash
# The node under load over live UDP multicast, only inside a network
# namespace this test creates (deps.md; as test_udp.sh), on the default
# udpm:// URL (the node adds recv_buf_size itself): a slow plan in progress
# while 100 goals arrive, a burst of 2,000 goals as fast as the client can
# publish, 20 maps at the node's capacity, and the start-up warning when the
# kernel caps the receive buffer. Where namespaces are unavailable the
# checks are reported as skipped, never as passed.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
NAMES=("a plan in progress while 100 goals arrive: 101 answers, none missing or doubled"
       "a 2,000-goal burst: answered equals sent equals received by the node"
       "a map at capacity (512 x 512 cells) over udpm:// is taken 20 of 20 times"
       "the node says so when the kernel caps its receive buffer")

tap_need_netns "${NAMES[@]}"

unshare --net env B="$B" T="$T" bash -c '
set -u
. tests/node/wait.sh
trap "kill \$(jobs -p) 2>/dev/null" EXIT   # nothing outlives a failed wait
ip link set lo up && ip route add 224.0.0.0/4 dev lo || exit 3
NODE=$B/test/node/hylo-planner-synthetic
BURST=$B/test/node/goal_burst
$NODE 2> "$T/node.err" &
node=$!
wait_receivers 1 || exit 4
$BURST --slow --goals 100 --rate 2000 --timeout 120 > "$T/slow.json" 2> "$T/slow.err"; echo $? > "$T/slow.rc"
$BURST --goals 2000 --rate 0 --requesters 4 --timeout 120 > "$T/burst.json" 2> "$T/burst.err"; echo $? > "$T/burst.rc"
$BURST --maps 20 > "$T/maps.json" 2> "$T/maps.err"; echo $? > "$T/maps.rc"
kill -TERM $node; wait $node
$NODE --recv-buf 1073741824 --once 2> "$T/capped.err" &
capped=$!
wait_catching $capped   # its warning comes before its handlers
kill -TERM $capped; wait $capped
exit 0
'
rc=$?
if [ "$rc" -eq 3 ]; then
  for n in "${NAMES[@]}"; do tap_skip "$n" "namespace set-up failed (exit $rc)"; done
  tap_finish; exit
elif [ "$rc" -ne 0 ]; then
  for n in "${NAMES[@]}"; do tap_not_ok "$n" "the node never got ready (exit $rc): $(cat "$T/node.err")"; done
  tap_finish; exit
fi
field() { sed -n "s/.*\"$2\":\([0-9.-]*\).*/\1/p" "$T/$1.json"; }

if [ "$(cat "$T/slow.rc")" = 0 ] && [ "$(field slow answered)" = 101 ] &&
   [ "$(field slow missing)" = 0 ] && [ "$(field slow duplicates)" = 0 ]; then
  tap_ok "${NAMES[0]}"; else tap_not_ok "${NAMES[0]}" "$(cat "$T/slow.json" "$T/slow.err")"; fi
echo "# slow: $(cat "$T/slow.json")"
if [ "$(cat "$T/burst.rc")" = 0 ] && [ "$(field burst answered)" = 2000 ] &&
   [ "$(field burst node_received)" = "$(field burst node_answered)" ] &&
   [ "$(field burst duplicates)" = 0 ]; then
  tap_ok "${NAMES[1]}"; else tap_not_ok "${NAMES[1]}" "$(cat "$T/burst.json" "$T/burst.err")"; fi
echo "# burst: $(cat "$T/burst.json")"
if [ "$(cat "$T/maps.rc")" = 0 ] && [ "$(field maps maps_taken)" = 20 ]; then
  tap_ok "${NAMES[2]}"; else tap_not_ok "${NAMES[2]}" "$(cat "$T/maps.json" "$T/maps.err")"; fi
echo "# maps: $(cat "$T/maps.json")"
if grep -q "the kernel caps the UDP receive buffer" "$T/capped.err"; then
  tap_ok "${NAMES[3]}"; else tap_not_ok "${NAMES[3]}" "$(cat "$T/capped.err")"; fi
tap_finish
