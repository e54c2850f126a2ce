#!/usr/bin/env bash
# The planner node as a process, driven through LCM file:// logs: the scene
# publisher writes maps and goals to a log, the node reads it and writes its
# plans to another log, and plan_check compares every plan with the library's
# own answer. Also: --once, clean exit on SIGTERM/SIGINT, usage errors,
# --margin and the body radii of --list-robots.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
. tests/node/wait.sh
B=${BUILD:-build}
NODE=$B/test/node/hylo-planner-synthetic
SCENE=$B/bin/hylo-scene
LISTEN=$B/bin/hylo-listen
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

# Requests: two goals, a goal starting inside an obstacle, a map for an
# unknown robot followed by a goal, the good map again and a Dijkstra goal.
log() { local n=$1; shift; "$SCENE" "$@" --lcm-url "file://$T/part$n.log?mode=w"; }
sed 's/^robot: synthetic/robot: nobody/' tests/node/synthetic.yaml > "$T/nobody.yaml"
log 1 tests/node/synthetic.yaml --goal --request-id 1
log 2 tests/node/synthetic.yaml --goal --request-id 2 --start ground:2,18,1,0
log 3 tests/node/synthetic.yaml --goal --request-id 3 --start ground:11,5,0,0
log 4 "$T/nobody.yaml" --goal --request-id 4
log 5 tests/node/synthetic.yaml --goal --request-id 5 --seed 11
cat "$T"/part[1-5].log > "$T/in.log"

if "$NODE" --lcm-url "file://$T/in.log?speed=0" --out-url "file://$T/out.log?mode=w" \
     2> "$T/node.err"; then
  tap_ok "node reads a file:// log and exits 0 at its end"
else
  tap_not_ok "node reads a file:// log and exits 0 at its end" "$(cat "$T/node.err")"
fi
tap_check "every plan equals the library's answer (plan_check)" \
  "$B/test/node/plan_check" "$T/in.log" "$T/out.log"
n=$(grep -c '^request ' "$T/node.err")
if [ "$n" -eq 5 ]; then tap_ok "one log line per request"; else
  tap_not_ok "one log line per request" "got $n lines" "$(cat "$T/node.err")"; fi

"$LISTEN" --lcm-url "file://$T/out.log?speed=0" --json > "$T/plans.jsonl"
if python3 - "$T/plans.jsonl" <<'PY'
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1])]
rows = [r for r in lines if r["type"] == "plan"]
# Goals ask for the default alternatives: a robot of one mode has one sequence.
alts = [(r["request_id"], r["index"], r["count"]) for r in lines if r["type"] == "alternative"]
assert alts == [(1, 0, 1), (2, 0, 1), (5, 0, 1)], alts
want = [(1, "ok"), (2, "ok"), (3, "bad request"), (4, "bad request"), (5, "ok")]
got = [(r["request_id"], r["status"]) for r in rows]
assert got == want, got
assert "nobody" in rows[3]["reason"], rows[3]["reason"]
assert rows[0]["waypoints"][0]["state"][:2] == [2, 2]
assert rows[0]["total_cost_j"] > 0 and rows[0]["mode_sequence"] == ["ground"]
PY
then tap_ok "hylo-listen --json: statuses and reasons per request"; else
  tap_not_ok "hylo-listen --json: statuses and reasons per request" "$(cat "$T/plans.jsonl" | cut -c1-300)"; fi

# --once: the node stops after its first answer although more goals follow.
"$NODE" --once --lcm-url "file://$T/in.log?speed=0" --out-url "file://$T/once.log?mode=w" 2> "$T/once.err"
rc=$?
n=$("$LISTEN" --lcm-url "file://$T/once.log?speed=0" | grep -c '^plan ')
if [ "$rc" -eq 0 ] && [ "$n" -eq 1 ]; then tap_ok "--once answers one goal and exits 0"; else
  tap_not_ok "--once answers one goal and exits 0" "exit $rc, $n plans"; fi

# Signals: a node waiting on an idle in-process bus stops cleanly.
for sig in TERM INT; do
  "$NODE" --lcm-url memq:// 2> "$T/sig.err" &
  pid=$!
  wait_catching "$pid"
  kill -s "$sig" "$pid"
  wait "$pid"
  rc=$?
  if [ "$rc" -eq 0 ]; then tap_ok "SIG$sig: clean exit 0"; else tap_not_ok "SIG$sig: clean exit 0" "exit $rc"; fi
done

# Usage.
"$NODE" --help > "$T/help.txt"; rc=$?
if [ "$rc" -eq 0 ] && grep -q -- "--channel-prefix" "$T/help.txt" && grep -q -- "--once" "$T/help.txt"; then
  tap_ok "--help lists the options"; else tap_not_ok "--help lists the options" "exit $rc"; fi
"$NODE" --no-such-option 2> "$T/usage.err"; rc=$?
if [ "$rc" -eq 2 ] && grep -q "no-such-option" "$T/usage.err"; then
  tap_ok "unknown option: exit 2 naming it"; else tap_not_ok "unknown option: exit 2 naming it" "exit $rc"; fi
"$NODE" --lcm-url "file://$T/in.log" 2> "$T/usage.err"; rc=$?
if [ "$rc" -eq 2 ] && grep -q -- "--out-url" "$T/usage.err"; then
  tap_ok "reading a log without --out-url: exit 2 saying so"; else
  tap_not_ok "reading a log without --out-url: exit 2 saying so" "exit $rc"; fi
"$NODE" --lcm-url "nosuch://x" 2> "$T/url.err"; rc=$?
if [ "$rc" -eq 1 ] && grep -q "nosuch" "$T/url.err"; then
  tap_ok "bad LCM URL: exit 1 naming it"; else tap_not_ok "bad LCM URL: exit 1 naming it" "exit $rc"; fi

# Body and margin: a start 0.05 m from the wall lacks the default margin
# (the synthetic robot has no robot file: no body) and is refused naming
# it; with --margin 0 it is planned. Bad margins are usage errors.
log 6 tests/node/synthetic.yaml --goal --request-id 6 --start ground:9.95,5,0,0
for m in default 0; do
  args=(); [ "$m" = default ] || args=(--margin "$m")
  "$NODE" "${args[@]}" --lcm-url "file://$T/part6.log?speed=0" --out-url "file://$T/margin_$m.log?mode=w" 2> /dev/null
  "$LISTEN" --lcm-url "file://$T/margin_$m.log?speed=0" --json > "$T/margin_$m.jsonl"
done
if python3 - "$T/margin_default.jsonl" "$T/margin_0.jsonl" <<'PY'
import json, sys
a, b = (json.loads(open(f).readline()) for f in sys.argv[1:3])
assert a["status"] == "bad request", a
assert "start (9.95, 5, 0) is 0.05 m from the nearest ground hazard; robot synthetic needs 0.1 m (body 0 m + margin 0.1 m)" in a["reason"], a["reason"]
assert b["status"] == "ok", b
PY
then tap_ok "a start without the default margin is refused naming it; --margin 0 plans it"; else
  tap_not_ok "a start without the default margin is refused naming it; --margin 0 plans it" "$(cut -c1-300 "$T"/margin_*.jsonl)"; fi
for bad in -0.1 nan inf 1x ""; do
  "$NODE" --margin "$bad" 2> "$T/margin.err"; rc=$?
  if [ "$rc" -eq 2 ] && grep -q -- "--margin '$bad': a clearance in metres, finite and >= 0" "$T/margin.err"; then
    tap_ok "--margin '$bad': exit 2 saying what it wants"; else
    tap_not_ok "--margin '$bad': exit 2 saying what it wants" "exit $rc: $(cat "$T/margin.err")"; fi
done
"$NODE" --list-robots > "$T/robots.txt"; rc=$?
if [ "$rc" -eq 0 ] && grep -q "^ambot: .*, body radius 0.35 m$" "$T/robots.txt" &&
   grep -q "^drivocopter: .*, body radius 0.32 m$" "$T/robots.txt" &&
   grep -q "^di: .*, body radius 0 m$" "$T/robots.txt" &&
   grep -q "^synthetic: .*, body radius 0 m (no robot file)$" "$T/robots.txt" &&
   grep -q -- "--margin M" "$T/help.txt"; then
  tap_ok "--list-robots prints the robot files' body radii; --help lists --margin"; else
  tap_not_ok "--list-robots prints the robot files' body radii; --help lists --margin" "$(cat "$T/robots.txt")"; fi

# hylo-cost: the model's prediction for one edge, as text and JSON.
COST=$B/test/node/hylo-cost-synthetic
out=$("$COST" --robot synthetic --mode ground --json 0,0,0,0 3,4,1,0 2>&1)
if python3 -c 'import json,sys; d=json.loads(sys.argv[1]); assert d["distance_m"] == 5 and 10 < d["predicted_cost_j"] < 40 and d["feasibility"] is None, d' "$out"; then
  tap_ok "hylo-cost --json predicts a plausible cost for a 5 m edge"; else
  tap_not_ok "hylo-cost --json predicts a plausible cost for a 5 m edge" "$out"; fi
"$COST" --robot synthetic --mode ground 0,0,0 3,4,1,0 2> "$T/cost.err"; rc=$?
if [ "$rc" -eq 2 ] && grep -q "not 4 comma-separated" "$T/cost.err"; then
  tap_ok "hylo-cost: malformed state, exit 2"; else tap_not_ok "hylo-cost: malformed state, exit 2" "exit $rc"; fi
"$COST" --robot synthetic --mode marine 0,0,0,0 3,4,1,0 2> "$T/cost.err"; rc=$?
if [ "$rc" -eq 1 ] && grep -q "no model" "$T/cost.err"; then
  tap_ok "hylo-cost: no model for the mode, exit 1"; else tap_not_ok "hylo-cost: no model for the mode, exit 1" "exit $rc"; fi

# Scene publisher: bad scene files are refused with file and line.
printf 'robot: synthetic\ngrid: {nx: 4, ny: 4, resolution_m: -1}\n' > "$T/bad.yaml"
"$SCENE" "$T/bad.yaml" --check 2> "$T/scene.err"; rc=$?
if [ "$rc" -eq 1 ] && grep -q "bad.yaml:2: resolution_m must be > 0" "$T/scene.err"; then
  tap_ok "hylo-scene: invalid scene names file and line"; else
  tap_not_ok "hylo-scene: invalid scene names file and line" "exit $rc: $(cat "$T/scene.err")"; fi
for s in scenes/*.yaml; do
  tap_check "hylo-scene --check $s" "$SCENE" "$s" --check
done
tap_finish
