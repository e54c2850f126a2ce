#!/usr/bin/env bash
# The trainer's command line and datasets (on the cheap double-integrator
# mode): usage errors, parameter-file errors, --ipopt-option and --debug,
# the settings a dataset's .meta records, --solve --json, determinism
# across worker counts, resume after a kill, shards that concatenate to the
# unsharded file, a small gen -> fit -> export run whose header compiles,
# --compare, and workers that die with a killed trainer (a short marine gen).
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
TR=$B/bin/trainer
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

expect_fail() {  # NAME CODE NEEDLE CMD...
  local name=$1 code=$2 needle=$3; shift 3
  "$@" > "$T/out" 2> "$T/err"; local rc=$?
  if [ "$rc" -eq "$code" ] && grep -q -- "$needle" "$T/err"; then tap_ok "$name"; else
    tap_not_ok "$name" "exit $rc (want $code)" "$(head -3 "$T/err")"; fi
}

"$TR" --help > "$T/help"; rc=$?
if [ "$rc" -eq 0 ] && grep -q -- "--samples N" "$T/help" && grep -q "default: ground and marine 8640" "$T/help" && grep -q -- "--shard K/N" "$T/help"; then
  tap_ok "--help lists the options with their defaults"; else tap_not_ok "--help lists the options with their defaults"; fi
if grep -q -- "--ipopt-option NAME=VALUE" "$T/help" && grep -A2 -- "--ipopt-option NAME=VALUE" "$T/help" | grep -q "default: none" &&
   grep -A1 -- "--debug" "$T/help" | grep -q "default: off" && grep -q -- "--version" "$T/help"; then
  tap_ok "--help lists --ipopt-option, --debug and --version with their defaults"; else
  tap_not_ok "--help lists --ipopt-option, --debug and --version with their defaults"; fi
expect_fail "unknown Ipopt option: exit 2" 2 "Ipopt has no option 'bogus'" \
  "$TR" --mode di_neg --robot di --solve -0.5,0 -0.3,0 --ipopt-option bogus=1
expect_fail "an Ipopt option value of the wrong type: exit 2" 2 "Ipopt refuses '1.5' for max_iter" \
  "$TR" --mode di_neg --robot di --solve -0.5,0 -0.3,0 --ipopt-option max_iter=1.5
expect_fail "--ipopt-option without a value: exit 2" 2 "'tol' is not NAME=VALUE" \
  "$TR" --mode di_neg --robot di --solve -0.5,0 -0.3,0 --ipopt-option tol
"$TR" --mode di_neg --robot di --solve -0.5,0 -0.3,0 --debug --ipopt-option mu_strategy=adaptive > "$T/out" 2> "$T/err"
if grep -q "^start T=.* relax 1: solved" "$T/err" && grep -q "^  replay di_neg: error" "$T/err" && grep -q "converged" "$T/out" &&
   ! grep -q "^start" "$T/out"; then
  tap_ok "--debug traces every solve and replay on stderr"; else
  tap_not_ok "--debug traces every solve and replay on stderr" "$(head -3 "$T/err")"; fi
if grep -q "^robots in trainer/params/:" "$T/help" && grep -q "^  ambot (ground, marine)$" "$T/help" &&
   grep -q "^  di (di_neg, di_pos)$" "$T/help" && grep -q "^  drivocopter (flight, ground)$" "$T/help"; then
  tap_ok "--help lists the robots and their modes"; else tap_not_ok "--help lists the robots and their modes"; fi
# A missing --robot or --mode: exit 2, the robots (or modes) that exist, a command that works.
expect_fail "--mode without --robot: exit 2" 2 "--robot is required" "$TR" --mode ground
if grep -q "robots in trainer/params/ with mode ground:" "$T/err" && grep -q "^  ambot (ground, marine)$" "$T/err" &&
   grep -q "^  drivocopter (flight, ground)$" "$T/err" && ! grep -q "^  di " "$T/err" &&
   grep -q "^e.g. trainer --mode ground --robot ambot$" "$T/err"; then
  tap_ok "--mode ground without --robot lists the robots with that mode and a command"; else
  tap_not_ok "--mode ground without --robot lists the robots with that mode and a command" "$(cat "$T/err")"; fi
expect_fail "--robot without --mode: exit 2, its modes" 2 "robot di has modes di_neg, di_pos" "$TR" --robot di
expect_fail "neither: exit 2, every robot" 2 "^  di (di_neg, di_pos)$" "$TR"
expect_fail "unknown robot: exit 2, the robots that exist" 2 "^  ambot (ground, marine)$" "$TR" --mode ground --robot nobot
expect_fail "robot without that mode: exit 2, the robots with it" 2 "^  drivocopter (flight, ground)$" \
  "$TR" --mode flight --robot ambot --solve 0,0,0,0,0,0 1,0,0,0,0,0
mkdir -p "$T/onlydi"
cp trainer/params/di.yaml "$T/onlydi/mydi.yaml"
expect_fail "the list follows HYLO_PARAMS_DIR" 2 "^  mydi (di_neg, di_pos)$" env HYLO_PARAMS_DIR="$T/onlydi" "$TR" --mode di_neg
expect_fail "unknown mode: exit 2" 2 "unknown mode 'swim'" "$TR" --mode swim --robot ambot --solve 0 0
expect_fail "unknown robot: exit 2 naming the file" 2 "trainer/params/nobot.yaml" "$TR" --mode ground --robot nobot --solve 0 0
expect_fail "malformed --solve vector: exit 2" 2 "'x' in '0,x,0,0'" "$TR" --mode ground --robot ambot --solve 0,x,0,0 1,0,0,0
expect_fail "wrong --solve length: exit 2" 2 "needs 4" "$TR" --mode ground --robot ambot --solve 0,0,0 1,0,0,0
expect_fail "--draws the mode does not have: exit 2" 2 "di_neg pairs are drawn as 1 or 2" \
  "$TR" --mode di_neg --robot di --draws 3 --stage gen --samples 1 --out "$T/draws"
expect_fail "out-of-bounds boundary state: exit 2" 2 "outside" "$TR" --mode di_neg --robot di --solve 0.5,0 -0.3,0
expect_fail "robot without that mode: exit 2" 2 "no mode 'flight'" "$TR" --mode flight --robot ambot --solve 0,0,0,0,0,0 1,0,0,0,0,0
expect_fail "unusable output directory: clear error" 1 "cannot create the output directory" \
  "$TR" --mode di_neg --robot di --samples 4 --stage gen --out /proc/no/such/dir --quiet

mkdir -p "$T/params"
cp trainer/params/di.yaml "$T/params/good.yaml"
sed 's/rho: 0.1}/rho: 0.1, bogus: 2}/' trainer/params/di.yaml | sed '0,/bogus/s//bogus/' > "$T/params/unknown.yaml"
sed 's/{rho: 0.1}/{}/' trainer/params/di.yaml > "$T/params/missing.yaml"
sed 's/rho: 0.1}/rho: -3}/' trainer/params/di.yaml > "$T/params/badvalue.yaml"
expect_fail "parameter file: unknown key names file, key and line" 2 "unknown.yaml:9: unknown key 'bogus'" \
  env HYLO_PARAMS_DIR="$T/params" "$TR" --mode di_neg --robot unknown --solve -0.5,0 -0.3,0
expect_fail "parameter file: missing key names file, key and line" 2 "missing.yaml:9: missing key 'rho'" \
  env HYLO_PARAMS_DIR="$T/params" "$TR" --mode di_neg --robot missing --solve -0.5,0 -0.3,0
expect_fail "parameter file: bad value names file, key and line" 2 "badvalue.yaml:9: di_neg.rho must be > 0" \
  env HYLO_PARAMS_DIR="$T/params" "$TR" --mode di_neg --robot badvalue --solve -0.5,0 -0.3,0
sed 's/^  radius_m: 0$/  radius_m: -0.2/' trainer/params/di.yaml > "$T/params/badbody.yaml"
expect_fail "parameter file: a negative body radius names file, key and line" 2 "badbody.yaml:6: body.radius_m must be in" \
  env HYLO_PARAMS_DIR="$T/params" "$TR" --mode di_neg --robot badbody --solve -0.5,0 -0.3,0
sed 's/^\(    params: {rho: 0.1}\)$/\1\n    solver: {refinements: 2.5}/' trainer/params/di.yaml > "$T/params/badsolver.yaml"
expect_fail "parameter file: bad solver setting names file, key and line" 2 \
  "badsolver.yaml:10: refinements must be an integer in .0, 5." \
  env HYLO_PARAMS_DIR="$T/params" "$TR" --mode di_neg --robot badsolver --solve -0.5,0 -0.3,0

"$TR" --mode di_neg --robot di --solve -0.5,0 -0.3,0 --json --trajectory > "$T/solve.json"
if python3 - "$T/solve.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["converged"] and abs(d["T_s"] - 1.9480074928505935) < 1e-4, d
assert d["replay_error"] < 1e-6 and d["iterations"] > 0
t = d["trajectory"]
assert len(t["t_s"]) == len(t["x"]) == len(t["u"]) == 41 and len(t["x"][0]) == 2
assert t["x"][0] == [-0.5, 0] and abs(t["x"][-1][0] + 0.3) < 1e-12
PY
then tap_ok "--solve --json --trajectory: cost, T, replay and samples"; else tap_not_ok "--solve --json --trajectory: cost, T, replay and samples" "$(head -c 300 "$T/solve.json")"; fi

gen() { "$TR" --mode di_neg --robot di --stage gen --quiet --samples 36 --seed 3 "$@"; }
gen --jobs 1 --out "$T/j1" > /dev/null && gen --jobs 2 --out "$T/j2" > /dev/null
tap_check "--jobs 1 and --jobs 2 write byte-identical datasets" cmp "$T/j1/di_neg.csv" "$T/j2/di_neg.csv"
n=$(($(wc -l < "$T/j1/di_neg.csv") - 1))
if [ "$n" -eq 36 ]; then tap_ok "one row per sample"; else tap_not_ok "one row per sample" "$n rows"; fi

for k in 1 2 3; do gen --jobs 2 --shard $k/3 --out "$T/sh" > /dev/null; done
cat "$T/sh/di_neg.shard-1-of-3.csv" "$T/sh/di_neg.shard-2-of-3.csv" "$T/sh/di_neg.shard-3-of-3.csv" > "$T/sh/all.csv"
tap_check "shards 1/3, 2/3, 3/3 concatenate to the unsharded file" cmp "$T/sh/all.csv" "$T/j1/di_neg.csv"

# Interrupted: killed after its first chunks, then run again.
"$TR" --mode di_neg --robot di --stage gen --quiet --samples 96 --seed 3 --jobs 2 --out "$T/kill" > /dev/null &
pid=$!
for i in $(seq 1 1200); do
  [ -f "$T/kill/di_neg.csv" ] && [ "$(wc -l < "$T/kill/di_neg.csv")" -gt 40 ] && break
  sleep 0.05
done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
printf '17,0.1,0.2,garbage' >> "$T/kill/di_neg.csv"    # a torn last row
before=$(($(wc -l < "$T/kill/di_neg.csv") - 1))
gen --samples 96 --jobs 2 --out "$T/kill" > "$T/resume.out"
gen --samples 96 --jobs 1 --out "$T/full" > /dev/null
if cmp -s "$T/kill/di_neg.csv" "$T/full/di_neg.csv" && [ "$before" -lt 96 ]; then
  tap_ok "killed after $before rows and re-run: the same file as an uninterrupted run"; else
  tap_not_ok "killed and re-run: the same file as an uninterrupted run" "$before rows before; $(cat "$T/resume.out")"; fi
"$TR" --mode di_neg --robot di --stage gen --quiet --samples 4 --seed 3 --out "$T/opt" --ipopt-option mu_init=0.1 \
  --ipopt-option tol=1e-9 > /dev/null
if grep -q "^ipopt_options: mu_init=0.1 tol=1e-9$" "$T/opt/di_neg.csv.meta" && grep -q "^tol: 1e-08$" "$T/opt/di_neg.csv.meta" &&
   grep -q "^refine_within: inf$" "$T/opt/di_neg.csv.meta" && grep -q "^blas: " "$T/opt/di_neg.csv.meta"; then
  tap_ok "the .meta records the solver settings, the --ipopt-option list and the numerics"; else
  tap_not_ok "the .meta records the solver settings, the --ipopt-option list and the numerics" "$(cat "$T/opt/di_neg.csv.meta")"; fi
expect_fail "extending it without those Ipopt options is refused, naming the line" 1 \
  "ipopt_options: mu_init=0.1 tol=1e-9 vs ipopt_options: none" \
  "$TR" --mode di_neg --robot di --stage gen --quiet --samples 8 --seed 3 --out "$T/opt"
expect_fail "a dataset made with other arguments is not silently extended" 1 "made under other settings: seed: 3 vs seed: 4" \
  "$TR" --mode di_neg --robot di --stage gen --quiet --samples 200 --seed 4 --out "$T/kill"

# A small pipeline: gen -> fit -> export, and the header compiles into the planner.
mkdir -p "$T/models"
if "$TR" --mode di_neg --robot di --samples 150 --seed 5 --jobs 2 --quiet --out "$T/pipe" --models-dir "$T/models" > "$T/pipe.out" 2>&1 &&
   gcc -std=c99 -Wall -Wextra -Werror -pedantic -Ionboard/include -I"$T/models" -x c - -x none -o "$T/use" $B/lib/libhylo.a -lm <<'C'
#include "di_di_neg.h"
#include "hylo/features.h"
#include <stdio.h>
int main(void)
{
	double a[6] = {-0.5, 0}, b[6] = {-0.3, 0}, f[4];
	hylo_features(HYLO_MODE_DI_NEG, a, b, f);
	printf("%.6f\n", hylo_svr_predict(&hylo_model_di_di_neg, f));
	return hylo_svr_check(&hylo_model_di_di_neg, NULL) != HYLO_OK;
}
C
then
  pred=$("$T/use")
  if python3 -c "import sys; p=float(sys.argv[1]); assert abs(p - 0.2597) < 0.25 * 0.2597, p" "$pred"; then
    tap_ok "gen -> fit -> export: the header compiles and predicts the 0.2597 optimum within 25% (a 150-sample model) ($pred)"; else
    tap_not_ok "gen -> fit -> export: the header compiles and predicts the 0.2597 optimum within 25% (a 150-sample model)" "predicted $pred"; fi
else
  tap_not_ok "gen -> fit -> export: the header compiles and predicts the 0.2597 optimum within 25% (a 150-sample model)" "$(tail -5 "$T/pipe.out")"
fi
grep "^fit" "$T/pipe.out" | sed 's/^/# /'

# Fitting on a dataset's first rows (a dataset grows at its end): --samples
# 100 on the 150-row file gives the bytes of a fit on a 100-row copy, and
# the header names the hash of those rows.
mkdir -p "$T/first" "$T/cut"
cp "$T/pipe/di_neg.csv" "$T/pipe/di_neg.csv.meta" "$T/first/"
head -n 101 "$T/pipe/di_neg.csv" > "$T/cut/di_neg.csv"
cp "$T/pipe/di_neg.csv.meta" "$T/cut/"
"$TR" --mode di_neg --robot di --stage fit --samples 100 --seed 5 --quiet --out "$T/first" > /dev/null 2>&1
"$TR" --mode di_neg --robot di --stage fit --seed 5 --quiet --out "$T/cut" > /dev/null 2>&1
if [ -s "$T/first/di_di_neg.h" ] && cmp -s "$T/first/di_di_neg.h" "$T/cut/di_di_neg.h" &&
   grep -q "samples: 100 " "$T/first/di_di_neg.h" &&
   grep -q "dataset sha256: $(sha256sum < "$T/cut/di_neg.csv" | cut -d' ' -f1)" "$T/first/di_di_neg.h"; then
  tap_ok "--stage fit --samples 100 fits the first 100 rows and names their hash"; else
  tap_not_ok "--stage fit --samples 100 fits the first 100 rows and names their hash" "$(grep -E 'samples|dataset' "$T/first/di_di_neg.h" | head -2)"; fi

# --compare HEADER: the held-out errors of another model on the fit's own
# held-out rows. The fit's own header gives the fit's figures; the
# 100-row model gives other ones; a header of another mode is refused
# before any fitting.
mkdir -p "$T/cmp"
cp "$T/pipe/di_neg.csv" "$T/pipe/di_neg.csv.meta" "$T/cmp/"
"$TR" --mode di_neg --robot di --stage fit --seed 5 --quiet --out "$T/cmp" > "$T/cmp/own.out" 2>&1
cp "$T/cmp/di_di_neg.h" "$T/cmp/own.h"
"$TR" --mode di_neg --robot di --stage fit --seed 5 --quiet --out "$T/cmp" --compare "$T/cmp/own.h" > "$T/cmp/same.out" 2>&1
"$TR" --mode di_neg --robot di --stage fit --seed 5 --quiet --out "$T/cmp" --compare "$T/first/di_di_neg.h" > "$T/cmp/other.out" 2>&1
figures() { grep -o 'median [0-9.]*, p95 [0-9.]*, max [0-9.]* relative; MAE [0-9.e-]* J' "$1" | sed -n "$2p"; }
own=$(figures "$T/cmp/own.out" 1)
if [ -n "$own" ] && [ "$(figures "$T/cmp/same.out" 1)" = "$own" ] && [ "$(figures "$T/cmp/same.out" 2)" = "$own" ] &&
   grep -q "own.h (.* SVs) on the same [0-9]* held-out rows" "$T/cmp/same.out" &&
   [ -n "$(figures "$T/cmp/other.out" 2)" ] && [ "$(figures "$T/cmp/other.out" 2)" != "$own" ] &&
   cmp -s "$T/cmp/di_di_neg.h" "$T/cmp/own.h"; then
  tap_ok "--compare: the fit's own header scores the fit's held-out figures on its held-out rows, another header others"; else
  tap_not_ok "--compare: the fit's own header scores the fit's held-out figures on its held-out rows, another header others" \
    "$(cat "$T/cmp/own.out" "$T/cmp/same.out" "$T/cmp/other.out")"; fi
echo "# $(grep 'on the same' "$T/cmp/other.out")"
expect_fail "--compare with a header of another mode: refused before the fit" 2 "not di di_neg" \
  "$TR" --mode di_neg --robot di --stage fit --seed 5 --quiet --out "$T/cmp" --compare onboard/models/di_di_pos.h
expect_fail "--compare with a missing header: clear error" 2 "--compare $T/cmp/none.h" \
  "$TR" --mode di_neg --robot di --stage fit --seed 5 --quiet --out "$T/cmp" --compare "$T/cmp/none.h"
expect_fail "--compare outside the fit: usage error" 2 "--compare HEADER is for the fit" \
  "$TR" --mode di_neg --robot di --stage export --out "$T/cmp" --compare "$T/cmp/own.h"

# Workers die with the trainer: killed by a scheduler or a test, it leaves
# no worker process solving on (a marine solve takes seconds, so a worker
# left behind would still be there half a second later).
mkdir -p "$T/killed"
"$TR" --mode marine --robot ambot --stage gen --samples 40 --jobs 2 --quiet --out "$T/killed" > /dev/null 2>&1 &
kpid=$!
workers=0
for _ in $(seq 1 100); do workers=$(pgrep -P "$kpid" | wc -l); [ "$workers" -ge 2 ] && break; sleep 0.1; done
sleep 0.5
kill "$kpid"; wait "$kpid" 2>/dev/null
sleep 0.5
left=$(pgrep -f -- "--out $T/killed" | wc -l)
if [ "$workers" -ge 1 ] && [ "$left" = 0 ]; then
  tap_ok "gen --jobs 2 killed: its workers ($workers running) die with it"; else
  tap_not_ok "gen --jobs 2 killed: its workers die with it" "$workers workers before, $left processes left"; fi
pkill -9 -f -- "--out $T/killed" 2>/dev/null

# Rows whose solve threw (status "error: ..."): read, never labels. A fit
# with three such rows gives the model of a fit on a copy without them.
mkdir -p "$T/errrows" "$T/noerrrows"
cp "$T/pipe/di_neg.csv.meta" "$T/errrows/"; cp "$T/pipe/di_neg.csv.meta" "$T/noerrrows/"
python3 - "$T/pipe/di_neg.csv" "$T/errrows/di_neg.csv" "$T/noerrrows/di_neg.csv" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head, data = rows[0], rows[1:]
ci, st, cost, t = (head.index(c) for c in ("converged", "status", "cost_j", "T_s"))
bad = {8, 48, 118}
with open(sys.argv[2], "w") as e, open(sys.argv[3], "w") as n:
    e.write(",".join(head) + "\n"); n.write(",".join(head) + "\n")
    for k, r in enumerate(data):
        if k in bad:
            r = list(r); r[ci] = "0"; r[cost] = "0"; r[t] = "0"; r[st] = "error: injected by the test"
            e.write(",".join(r) + "\n")
        else:
            e.write(",".join(r) + "\n"); n.write(",".join(r) + "\n")
PY
"$TR" --mode di_neg --robot di --stage fit --seed 5 --quiet --out "$T/errrows" > /dev/null 2> "$T/errrows.log"
"$TR" --mode di_neg --robot di --stage fit --seed 5 --quiet --out "$T/noerrrows" > /dev/null 2>&1
strip() { grep -v -E 'dataset sha256|samples:' "$1"; }
if [ -s "$T/errrows/di_di_neg.h" ] && [ -s "$T/noerrrows/di_di_neg.h" ] &&
   cmp -s <(strip "$T/errrows/di_di_neg.h") <(strip "$T/noerrrows/di_di_neg.h") &&
   grep -q "samples: 150 (.* converged, 3 errors left out)" "$T/errrows/di_di_neg.h" &&
   grep -q "3 rows whose solve ended in an error" "$T/errrows.log"; then
  tap_ok "rows whose solve ended in an error are left out of the fit (regression and classifier), and said so"; else
  tap_not_ok "rows whose solve ended in an error are left out of the fit (regression and classifier), and said so" \
    "$(grep 'samples:' "$T/errrows/di_di_neg.h"; cat "$T/errrows.log"; diff <(strip "$T/errrows/di_di_neg.h") <(strip "$T/noerrrows/di_di_neg.h") | head -5)"; fi

# Bad datasets: a clear error and no header.
mkdir -p "$T/bad" "$T/badmodels"
cp "$T/pipe/di_neg.csv.meta" "$T/bad/"
: > "$T/bad/di_neg.csv"
expect_fail "empty dataset: clear error, no header" 2 "empty" "$TR" --mode di_neg --robot di --stage fit --out "$T/bad" --quiet
head -5 "$T/pipe/di_neg.csv" > "$T/bad/di_neg.csv"; echo "1,2,3" >> "$T/bad/di_neg.csv"
expect_fail "corrupt dataset: clear error naming the line" 2 "di_neg.csv:6" "$TR" --mode di_neg --robot di --stage fit --out "$T/bad" --quiet
head -8 "$T/pipe/di_neg.csv" > "$T/bad/di_neg.csv"
expect_fail "too few samples for the folds: clear error" 2 "too few" "$TR" --mode di_neg --robot di --stage fit --out "$T/bad" --quiet
cp "$T/pipe/di_neg.csv" "$T/bad/"; sed -i 's/params_sha256: .*/params_sha256: 0000/' "$T/bad/di_neg.csv.meta"
expect_fail "a dataset from another robot file: clear error" 2 "another robot file" "$TR" --mode di_neg --robot di --stage fit --out "$T/bad" --quiet
# The body changes no label: a dataset outlives a new body radius, not a new parameter.
mkdir -p "$T/bodyparams" "$T/body"
cp "$T/pipe/di_neg.csv" "$T/pipe/di_neg.csv.meta" "$T/body/"
sed 's/^  radius_m: .*/  radius_m: 0.5/' trainer/params/di.yaml > "$T/bodyparams/di.yaml"
if ! cmp -s trainer/params/di.yaml "$T/bodyparams/di.yaml" &&
   env HYLO_PARAMS_DIR="$T/bodyparams" "$TR" --mode di_neg --robot di --stage fit --out "$T/body" --quiet > /dev/null 2>&1 &&
   [ -f "$T/body/di_di_neg.h" ]; then
  tap_ok "a robot file whose body changed still fits its dataset (params_sha256 leaves the body out)"; else
  tap_not_ok "a robot file whose body changed still fits its dataset (params_sha256 leaves the body out)"; fi
sed 's/rho: 0.1/rho: 0.2/' trainer/params/di.yaml > "$T/bodyparams/di.yaml"
expect_fail "a robot file whose parameters changed does not fit the dataset" 2 "another robot file" \
  env HYLO_PARAMS_DIR="$T/bodyparams" "$TR" --mode di_neg --robot di --stage fit --out "$T/body" --quiet
if ls "$T/bad"/*.h > /dev/null 2>&1; then tap_not_ok "no header written from bad data"; else tap_ok "no header written from bad data"; fi

# --stage repair (trainer/repair.hpp; the stage itself: test_repair).
expect_fail "repair without a dataset: clear error (exit 2)" 2 "run --stage gen first" \
  "$TR" --mode di_neg --robot di --stage repair --samples 4 --out "$T/norepair" --quiet
"$TR" --mode di_neg --robot di --stage gen --quiet --samples 10 --seed 3 --jobs 2 --out "$T/rep" > /dev/null
"$TR" --mode di_neg --robot di --stage repair --quiet --samples 8 --seed 3 --jobs 2 --neighbours 2 --out "$T/rep" > "$T/rep.out"; rc=$?
if [ "$rc" -eq 0 ] && grep -q "^repair di di_neg: 8 rows of .*labels lowered by more than 0.5%" "$T/rep.out" &&
   grep -q "^repaired_rows: 8$" "$T/rep/di_neg.csv.meta" && grep -q "^repair_neighbours: 2$" "$T/rep/di_neg.csv.meta" &&
   [ "$(grep -c . "$T/rep/di_neg.csv")" -eq 11 ] && grep -A1 -- "--neighbours K" "$T/help" | grep -q "default: 8"; then
  tap_ok "--stage repair --neighbours 2: repairs the first N rows, says how many it lowered, the .meta records it"
else tap_not_ok "--stage repair --neighbours 2: repairs the first N rows, says how many it lowered, the .meta records it" \
  "exit $rc" "$(cat "$T/rep.out")"; fi
expect_fail "repair of more rows than the dataset has: clear error (exit 2)" 2 "fewer than the 20 asked for" \
  "$TR" --mode di_neg --robot di --stage repair --samples 20 --seed 3 --out "$T/rep" --quiet
"$TR" --mode di_neg --robot di --stage gen --quiet --samples 12 --seed 3 --jobs 2 --out "$T/rep" > /dev/null &&
"$TR" --mode di_neg --robot di --stage repair --quiet --samples 12 --seed 3 --jobs 2 --neighbours 2 --out "$T/rep" > "$T/rep2.out"; rc=$?
if [ "$rc" -eq 0 ] && grep -q "^repair di di_neg: 12 rows of .* (8 kept from an earlier pass, .* 4 repaired now)" "$T/rep2.out" &&
   grep -q "^repaired_rows: 12$" "$T/rep/di_neg.csv.meta" && grep -q "^repair_passes: 8 12$" "$T/rep/di_neg.csv.meta" &&
   [ "$(grep -c . "$T/rep/di_neg.csv")" -eq 13 ]; then
  tap_ok "gen extends a repaired dataset; the repair then repairs only the rows past it and records both passes"
else tap_not_ok "gen extends a repaired dataset; the repair then repairs only the rows past it and records both passes" \
  "exit $rc" "$(cat "$T/rep2.out")"; fi
expect_fail "--refine-within x: clear error (exit 2)" 2 "fraction >= 0 or inf" \
  "$TR" --mode di_neg --robot di --refine-within x --solve -0.5,0 -0.3,0
"$TR" --mode di_neg --robot di --stage gen --quiet --samples 2 --seed 3 --refine-within 0.05 --out "$T/rw005" > /dev/null
if grep -q "^refine_within: 0.05$" "$T/rw005/di_neg.csv.meta" && grep -A3 -- "--refine-within F" "$T/help" | grep -q "default: inf"; then
  tap_ok "--refine-within 0.05 is recorded in the .meta; --help gives its default"
else tap_not_ok "--refine-within 0.05 is recorded in the .meta; --help gives its default" "$(grep refine "$T/rw005/di_neg.csv.meta")"; fi

# --mode switch: the robot's switches (docs/models.md section 6).
if "$TR" --mode switch --robot ambot --json > "$T/sw.json" &&
   python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); s=[(x["from"],x["to"],x["cost_j"]) for x in d["switches"]]; assert s == [("ground","marine",0),("marine","ground",0)], s' "$T/sw.json"; then
  tap_ok "--mode switch: Ambot's two shoreline switches at no cost"
else tap_not_ok "--mode switch: Ambot's two shoreline switches at no cost" "$(cat "$T/sw.json")"; fi
tap_finish
