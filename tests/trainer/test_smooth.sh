#!/usr/bin/env bash
# hylo-smooth end to end, through LCM file:// logs: the double integrator's
# scene planned by the node with the committed models, then smoothed. The
# smoothed cost must not exceed the exact cost of the graph path it starts
# from (every edge solved on its own), must be within 0.5% of the two-phase
# optimum found by sweeping the switching velocity on the guard p = 0, and
# must replay; bad input gets a traj_t whose status says why.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

. tests/trainer/plan_logs.sh
smooth() {
  local n=$1; shift
  "$B/bin/hylo-smooth" --lcm-url "file://$T/$n.all.log?speed=0" --out-url "file://$T/$n.traj.log?mode=w" "$@"
}
traj_json() { "$B/bin/hylo-listen" --lcm-url "file://$T/$1.traj.log?speed=0" --json; }

# sweep A0 A1 B0 B1: the best two-phase cost through (0, v), v swept densely
# then refined by golden section, every leg solved by trainer --solve.
sweep() {
  python3 - "$B/bin/trainer" "$@" <<'PY'
import json, subprocess, sys
tr, a0, a1, b0, b1 = sys.argv[1], *map(float, sys.argv[2:])
def leg(mode, x, y):
    out = subprocess.run([tr, "--mode", mode, "--robot", "di", "--solve", x, y, "--json"],
                         capture_output=True, text=True)
    d = json.loads(out.stdout)
    return d["cost_j"] if d["converged"] else float("inf")
def through(v):
    s = f"0,{v!r}"
    return leg("di_pos", f"{a0},{a1}", s) + leg("di_neg", s, f"{b0},{b1}")
grid = [-1 + 2 * i / 40 for i in range(41)]
best = min(grid, key=through)
lo, hi = max(-1, best - 0.05), min(1, best + 0.05)
g = (5 ** 0.5 - 1) / 2
for _ in range(18):
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    if through(x1) < through(x2): hi = x2
    else: lo = x1
print(min(through(best), through((lo + hi) / 2)))
PY
}

case_check() {
  local n=$1 a0=$2 a1=$3 b0=$4 b1=$5; shift 5
  plan_logs "$n" scenes/di.yaml "$@"
  if smooth "$n" --compare-graph > "$T/$n.out" 2> "$T/$n.err"; then
    tap_ok "$n: hylo-smooth reads the plan log and exits 0"
  else
    tap_not_ok "$n: hylo-smooth reads the plan log and exits 0" "$(cat "$T/$n.err")"
  fi
  sed 's/^/# /' "$T/$n.out"
  local swept; swept=$(sweep "$a0" "$a1" "$b0" "$b1")
  echo "# $n: swept two-phase optimum $swept"
  traj_json "$n" > "$T/$n.json"
  python3 - "$T/$n.json" "$T/$n.out" "$swept" "$a0" "$a1" "$b0" "$b1" > "$T/$n.check" 2>&1 <<'PY'
import json, re, sys
t = json.loads(open(sys.argv[1]).readline())
out = open(sys.argv[2]).read()
swept = float(sys.argv[3]); a = list(map(float, sys.argv[4:6])); b = list(map(float, sys.argv[6:8]))
graph = float(re.search(r"every edge solved exactly: ([0-9.eE+-]+) J", out).group(1))
E = t["energy_j"]
assert t["status"] == "ok", t["status"]
print("graph", E <= graph, f"smoothed {E} vs graph path {graph}")
print("swept", abs(E - swept) <= 5e-3 * swept, f"smoothed {E} vs swept {swept}")
print("replay", t["replay_error"] < 1e-4 and abs(t["replay_energy_j"] - E) < 1e-4 * E, str(t["replay_error"]))
x0, x1 = t["state"][0][:2], t["state"][-1][:2]
modes = t["mode"]
k = next(i for i in range(1, len(modes)) if modes[i] != modes[i - 1])
ends = max(abs(x0[0] - a[0]), abs(x0[1] - a[1]), abs(x1[0] - b[0]), abs(x1[1] - b[1]))
print("ends", ends < 1e-9 and abs(t["state"][k][0]) < 1e-9 and abs(t["state"][k - 1][0]) < 1e-9
      and sorted(set(modes)) == [4, 5], f"ends off by {ends}, switch at p = {t['state'][k][0]}")
PY
  tap_verdict "$T/$n.check" graph "$n: smoothed cost not above the exact cost of the graph path"
  tap_verdict "$T/$n.check" swept "$n: smoothed cost within 0.5% of the swept two-phase optimum"
  tap_verdict "$T/$n.check" replay "$n: the smoothed trajectory replays (CVODE) with its cost"
  tap_verdict "$T/$n.check" ends "$n: starts at the start, ends at the goal, switches on p = 0"
}

case_check di_case1 0.8 0.2 -0.8 0.0
case_check di_case2 0.7 -0.1 -0.5 0.2 --start di_pos:0.7,-0.1 --goal-state di_neg:-0.5,0.2

# Same input, same bytes out (the traj messages, publication time aside),
# with --debug tracing the solves on stderr and changing nothing else.
smooth di_case1 --quiet --debug 2> "$T/debug.err"
traj_json di_case1 > "$T/again.json"
if cmp -s "$T/again.json" "$T/di_case1.json"; then tap_ok "deterministic: a second run gives the same trajectory"
else tap_not_ok "deterministic: a second run gives the same trajectory"; fi
if grep -q '^start T=.* relax 1: solved' "$T/debug.err" && grep -q '^  replay di_' "$T/debug.err"; then
  tap_ok "--debug traces the solves and replays on stderr"
else tap_not_ok "--debug traces the solves and replays on stderr" "$(head -5 "$T/debug.err")"; fi

# A plan whose map was never seen, and a failed plan: answered, not dropped.
"$B/bin/hylo-smooth" --lcm-url "file://$T/di_case1.plan.log?speed=0" --out-url "file://$T/nomap.traj.log?mode=w" \
  2> "$T/nomap.err"
"$B/bin/hylo-listen" --lcm-url "file://$T/nomap.traj.log?speed=0" --json > "$T/nomap.json"
if grep -q '"status":"no map"' "$T/nomap.json" && grep -q "map 1 of the plan was not received" "$T/nomap.err"; then
  tap_ok "a plan whose map was not received gets a traj_t with status no map"
else tap_not_ok "a plan whose map was not received gets a traj_t with status no map" "$(cat "$T/nomap.json" "$T/nomap.err")"; fi
plan_logs bad scenes/di.yaml --start di_pos:2,0
smooth bad 2> "$T/bad.err" > /dev/null
traj_json bad > "$T/bad.json"
if grep -q '"status":"bad request"' "$T/bad.json" && grep -q "no path to smooth" "$T/bad.err"; then
  tap_ok "a failed plan gets a traj_t carrying its status and the reason"
else tap_not_ok "a failed plan gets a traj_t carrying its status and the reason" "$(cat "$T/bad.json" "$T/bad.err")"; fi

# Usage.
"$B/bin/hylo-smooth" --bogus > /dev/null 2> "$T/u.err"; rc=$?
if [ $rc -eq 2 ] && grep -q "unknown option '--bogus'" "$T/u.err"; then tap_ok "unknown option: exit 2 and says which"
else tap_not_ok "unknown option: exit 2 and says which" "rc $rc"; fi
"$B/bin/hylo-smooth" --segments-per-edge 0 > /dev/null 2> "$T/u.err"; rc=$?
if [ $rc -eq 2 ] && grep -q "an integer in \[1, 48\]" "$T/u.err"; then tap_ok "bad --segments-per-edge: exit 2"
else tap_not_ok "bad --segments-per-edge: exit 2" "rc $rc $(cat "$T/u.err")"; fi
"$B/bin/hylo-smooth" --ipopt-option mu_strategy=fancy > /dev/null 2> "$T/u.err"; rc=$?
if [ $rc -eq 2 ] && grep -q "Ipopt refuses 'fancy' for mu_strategy" "$T/u.err"; then tap_ok "bad --ipopt-option: exit 2 and says why"
else tap_not_ok "bad --ipopt-option: exit 2 and says why" "rc $rc $(cat "$T/u.err")"; fi
bad_margin=""
for m in -0.1 nan inf 11 0.1m ""; do
  "$B/bin/hylo-smooth" --margin "$m" > /dev/null 2> "$T/u.err"; rc=$?
  [ $rc -eq 2 ] && grep -q -- "--margin wants metres in \[0, 10\], not '$m'" "$T/u.err" || bad_margin="$bad_margin [$m: rc $rc $(cat "$T/u.err")]"
done
if [ -z "$bad_margin" ]; then tap_ok "bad --margin (negative, NaN, infinite, over 10, not a number, empty): exit 2 and says why"
else tap_not_ok "bad --margin (negative, NaN, infinite, over 10, not a number, empty): exit 2 and says why" "$bad_margin"; fi
if "$B/bin/hylo-smooth" --help | grep -q -- "--segments-per-edge N" && "$B/bin/hylo-smooth" --help | grep -q -- "--ipopt-option NAME=VALUE" &&
   "$B/bin/hylo-smooth" --help | grep -q -- "--margin M"; then tap_ok "--help lists the options"
else tap_not_ok "--help lists the options"; fi
tap_finish
