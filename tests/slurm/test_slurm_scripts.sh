#!/usr/bin/env bash
# tools/slurm/ without a cluster: the array task script takes N from its
# command line (not SLURM_ARRAY_TASK_COUNT) and refuses a task outside 1..N,
# the gather script stops with the gather step's exit code, the progress view
# counts tasks and rows from the shard files, and the submit script refuses
# bad usage before it submits anything.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
TR=$(readlink -f "$B/bin/trainer")
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
OPTS=(--robot di --mode di_neg --quiet --samples 30 --seed 2)

# Outside Slurm, as a task would run: SLURM_ARRAY_TASK_COUNT=1 as in a resubmission of one task.
for k in 1 3; do
	SLURM_ARRAY_TASK_ID=$k SLURM_ARRAY_TASK_COUNT=1 tools/slurm/shard.sbatch 3 "$TR" "${OPTS[@]}" --out "$T/out" > "$T/task$k.out" 2>&1
done
if [ -s "$T/out/di_neg.shard-3-of-3.csv" ] && grep -q "^shard 3/3: job" "$T/task3.out" && [ ! -e "$T/out/di_neg.shard-1-of-1.csv" ] &&
	[ ! -e "$T/out/di_neg.csv" ]; then
	tap_ok "task 3 with SLURM_ARRAY_TASK_COUNT=1 writes shard 3 of 3 (N from the command line)"; else
	tap_not_ok "task 3 writes shard 3 of 3" "$(cat "$T/task3.out")" "$(ls "$T/out")"; fi
SLURM_ARRAY_TASK_ID=4 tools/slurm/shard.sbatch 3 "$TR" "${OPTS[@]}" --out "$T/out" > "$T/out4" 2>&1; rc=$?
if [ $rc -eq 2 ] && grep -q "task 4 is outside 1..3" "$T/out4"; then tap_ok "task 4 of 3: exit 2"; else
	tap_not_ok "task 4 of 3: exit 2" "exit $rc: $(cat "$T/out4")"; fi
env -u SLURM_ARRAY_TASK_ID tools/slurm/shard.sbatch 3 "$TR" "${OPTS[@]}" --out "$T/out" > "$T/out0" 2>&1; rc=$?
if [ $rc -eq 2 ] && grep -q "not a job-array task" "$T/out0"; then tap_ok "outside a job array: exit 2"; else
	tap_not_ok "outside a job array: exit 2" "exit $rc: $(cat "$T/out0")"; fi

tools/slurm/progress --out "$T/out" --mode di_neg --shards 3 > "$T/p1" 2>&1; rc=$?
if [ $rc -eq 1 ] && grep -q "\] 2/3 tasks done, 1 not started; 20/30 rows (67%), .* rows/s, ETA .*; not done: 2$" "$T/p1"; then
	tap_ok "progress: 2 of 3 tasks, 20 of 30 rows, exit 1"; else tap_not_ok "progress: 2 of 3 tasks, 20 of 30 rows" "exit $rc: $(cat "$T/p1")"; fi
tools/slurm/gather.sbatch 3 fit "$T/models" "$TR" "${OPTS[@]}" --out "$T/out" > "$T/g1" 2>&1; rc=$?
if [ $rc -eq 1 ] && grep -q "^resubmit: --array=2$" "$T/g1" && [ ! -e "$T/out/di_neg.fit.json" ]; then
	tap_ok "the gather job stops with exit 1 and names shard 2, nothing fitted"; else
	tap_not_ok "the gather job stops with exit 1 and names shard 2" "exit $rc: $(cat "$T/g1")"; fi
SLURM_ARRAY_TASK_ID=2 tools/slurm/shard.sbatch 3 "$TR" "${OPTS[@]}" --out "$T/out" > /dev/null 2>&1
head -c -3 "$T/out/di_neg.shard-2-of-3.csv" > "$T/torn" && cp "$T/torn" "$T/out/di_neg.shard-2-of-3.csv"
tools/slurm/progress --out "$T/out" --mode di_neg --shards 3 > "$T/p2" 2>&1; rc=$?
if [ $rc -eq 1 ] && grep -q "2/3 tasks done, 0 not started; 29/30 rows" "$T/p2"; then
	tap_ok "progress counts complete rows only (a torn row is not one)"; else tap_not_ok "progress counts complete rows only" "exit $rc: $(cat "$T/p2")"; fi
SLURM_ARRAY_TASK_ID=2 tools/slurm/shard.sbatch 3 "$TR" "${OPTS[@]}" --out "$T/out" > /dev/null 2>&1
tools/slurm/gather.sbatch 3 gen-only "$T/models" "$TR" "${OPTS[@]}" --out "$T/out" > "$T/g2" 2>&1; rc=$?
"$TR" "${OPTS[@]}" --stage gen --out "$T/ref" > /dev/null
if [ $rc -eq 0 ] && grep -q "merged 3 shards, 30 rows" "$T/g2" && cmp -s "$T/out/di_neg.csv" "$T/ref/di_neg.csv" &&
	[ ! -e "$T/out/di_neg.fit.json" ]; then
	tap_ok "gen-only gather: merged, equal to the unsharded run, not fitted"; else
	tap_not_ok "gen-only gather: merged, equal to the unsharded run" "exit $rc: $(cat "$T/g2")"; fi
tools/slurm/progress --out "$T/out" --mode di_neg --shards 3 > "$T/p3" 2>&1; rc=$?
if [ $rc -eq 0 ] && grep -q "^\[#\{30\}\] 3/3 tasks done, 0 not started; 30/30 rows (100%)" "$T/p3"; then
	tap_ok "progress: every task done, exit 0"; else tap_not_ok "progress: every task done, exit 0" "exit $rc: $(cat "$T/p3")"; fi

expect_usage() {  # NAME NEEDLE CMD...
	local name=$1 needle=$2; shift 2
	"$@" > "$T/u" 2>&1; local rc=$?
	if [ $rc -eq 2 ] && grep -q -- "$needle" "$T/u"; then tap_ok "$name"; else tap_not_ok "$name" "exit $rc: $(cat "$T/u")"; fi
}
expect_usage "train --shards 1: exit 2" "--shards needs an integer >= 2, not '1'" \
	tools/slurm/train --robot di --mode di_neg --shards 1
expect_usage "train without --robot: exit 2" "--robot and --mode are required" tools/slurm/train --mode di_neg --shards 4
expect_usage "train with --stage among the trainer's options: exit 2" "--stage is set by this script" \
	tools/slurm/train --robot di --mode di_neg --shards 4 -- --stage all
expect_usage "progress --shards x: exit 2" "--shards needs an integer >= 2" \
	tools/slurm/progress --out "$T/out" --mode di_neg --shards x
tap_finish
