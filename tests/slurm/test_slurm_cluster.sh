#!/usr/bin/env bash
# Dataset generation as a Slurm job array, on a throwaway single-node cluster
# (tools/slurm/local-cluster: daemons as root in a temporary directory, torn
# down by PID): tools/slurm/train submits 4 real trainer shards (di_neg, 256
# samples); one task is killed mid-way and its shard torn, another shard is
# lost; the gather job (afterany) names exactly those two; running the same
# command again resubmits only them; the merged dataset and .meta equal an
# unsharded run's byte for byte. Skipped (and says why) without root or the
# packages slurm-wlm and munge (make slurm-deps; make test installs them).
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
TR=$(readlink -f "$B/bin/trainer")

skip_all() { tap_skip "Slurm job array of trainer shards on a local cluster" "$1"; tap_finish; exit 0; }
[ "$(id -u)" = 0 ] || skip_all "needs root (slurmd starts jobs as their user)"
for c in munged slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
	command -v "$c" > /dev/null || skip_all "$c missing (Debian packages slurm-wlm and munge: make slurm-deps)"
done

T=$(mktemp -d)
chmod 755 "$T"   # munged wants o+x on every directory above its socket
cleanup() {
	[ -f "$T/cluster/pids" ] && tools/slurm/local-cluster stop "$T/cluster"
	rm -rf "$T"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

N=4 S=256 W=64   # W rows per shard: two chunks of 32, so a task can be caught between them
OUT=$T/out
TRAIN=(tools/slurm/train --robot di --mode di_neg --shards $N --samples $S --seed 3 --out "$OUT" --gen-only --trainer "$TR")
rows() {  # complete rows of shard $1
	local f=$OUT/di_neg.shard-$1-of-$N.csv n=0
	[ -f "$f" ] && n=$(wc -l < "$f")
	[ "$1" = 1 ] && [ "$n" -gt 0 ] && n=$((n - 1))
	echo "$n"
}
job_state() { scontrol show job -o "$1" 2> /dev/null | sed -n 's/.*JobState=\([A-Z_]*\).* ExitCode=\([0-9:]*\).*/\1 \2/p'; }
wait_ended() {  # JOB SECONDS
	local i st
	for ((i = 0; i < $2 * 5; i++)); do
		st=$(job_state "$1")
		case "$st" in PENDING* | RUNNING* | CONFIGURING* | COMPLETING* | "") sleep 0.2 ;; *) echo "$st"; return 0 ;; esac
	done
	echo "still $st after $2 s"
}

"$TR" --mode di_neg --robot di --quiet --stage gen --samples $S --seed 3 --jobs 2 --out "$T/ref" > /dev/null ||
	tap_not_ok "the unsharded reference run"

t0=$(date +%s.%N)
if ! env_out=$(tools/slurm/local-cluster start "$T/cluster" 2> "$T/cluster.err"); then
	tap_not_ok "a local Slurm cluster starts" "$(tail -20 "$T/cluster.err")"
	tap_finish; exit 1
fi
eval "$env_out"
tap_ok "a local Slurm cluster starts ($(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s)"

"${TRAIN[@]}" > "$T/submit1.out" 2>&1
jid=$(sed -n 's/^submitted array job \([0-9]*\): .*/\1/p' "$T/submit1.out")
gid=$(sed -n 's/^submitted gather job \([0-9]*\).*/\1/p' "$T/submit1.out")
[ -n "$gid" ] && scontrol hold "$gid"   # released once the shards are damaged below
if [ -n "$jid" ] && [ -n "$gid" ] && grep -q "tasks 1-4 of 4" "$T/submit1.out"; then
	tap_ok "tools/slurm/train submits tasks 1-4 and a gather job"; else
	tap_not_ok "tools/slurm/train submits tasks 1-4 and a gather job" "$(cat "$T/submit1.out")"; fi
"${TRAIN[@]}" > "$T/again.out" 2>&1; rc=$?
if [ $rc -eq 2 ] && grep -q "still queued or running" "$T/again.out"; then
	tap_ok "a second submission while tasks are queued is refused (two tasks must not write one shard)"; else
	tap_not_ok "a second submission while tasks are queued is refused" "exit $rc: $(cat "$T/again.out")"; fi

# Kill a task between its two chunks.
killed=""
for ((i = 0; i < 600; i++)); do
	[ -z "$killed" ] || break
	for ((k = 1; k <= N; k++)); do
		r=$(rows $k)
		if [ "$r" -ge 32 ] && [ "$r" -lt $W ]; then
			scancel "${jid}_$k"
			until [ -z "$(squeue -h -j "${jid}_$k" -t pending,running,completing -o %i 2> /dev/null)" ]; do sleep 0.1; done
			[ "$(rows $k)" -lt $W ] && killed=$k
			break
		fi
	done
	sleep 0.1
done
until [ -z "$(squeue -h -j "$jid" -t pending,running,completing -o %i 2> /dev/null)" ]; do sleep 0.2; done
states=$(squeue -h -t all -j "$jid" -o '%K %T' | sort -n | paste -sd,)
if [ -n "$killed" ] && [[ ",$states," == *",$killed CANCELLED,"* ]]; then
	tap_ok "task $killed killed mid-way, after $(rows "$killed") of $W rows ($states)"; else
	tap_not_ok "a task killed mid-way" "no task caught between its chunks; tasks: $states"
	tap_finish; exit 1
fi
lost=$((killed % N + 1))
printf '%d,0.12,0.3' $(((killed - 1) * W + 32)) >> "$OUT/di_neg.shard-$killed-of-$N.csv"   # torn by the kill
rm -f "$OUT/di_neg.shard-$lost-of-$N.csv" "$OUT/di_neg.shard-$lost-of-$N.csv.meta"   # a task whose output was lost
want=$(printf '%s\n' "$killed" "$lost" | sort -n | paste -sd,)

tools/slurm/progress --out "$OUT" --mode di_neg --shards $N > "$T/progress1.out"; rc=$?
if [ $rc -eq 1 ] && grep -q "2/4 tasks done, 1 not started; 160/256 rows (62%), .* rows/s, ETA .*; not done: $want" "$T/progress1.out"; then
	tap_ok "progress from the shard files: $(cat "$T/progress1.out")"; else
	tap_not_ok "progress from the shard files: 2 of 4 tasks, 160 of 256 rows" "exit $rc: $(cat "$T/progress1.out")"; fi

scontrol release "$gid"
st=$(wait_ended "$gid" 60)
glog=$OUT/slurm-logs/hylo-di-di_neg-gather-$gid.log
if [ "$st" = "FAILED 1:0" ] && grep -q "^resubmit: --array=$want$" "$glog" && grep -q "^shard $killed/4 torn: " "$glog" &&
	grep -q "^shard $lost/4 missing: " "$glog"; then
	tap_ok "the gather job (afterany) ran after the failed task, exit 1, and names shards $want to resubmit"; else
	tap_not_ok "the gather job names the shards to resubmit" "state $st" "$(cat "$glog" 2> /dev/null)"; fi

t0=$(date +%s.%N)
timeout 300 "${TRAIN[@]}" --wait > "$T/submit2.out" 2>&1; rc=$?
jid2=$(sed -n 's/^submitted array job \([0-9]*\): .*/\1/p' "$T/submit2.out")
ran=$(squeue -h -t all -j "$jid2" -o '%K %T' 2> /dev/null | sort -n | tr '\n' ' ')
# shellcheck disable=SC2046
if [ $rc -eq 0 ] && [ "$ran" = "$(printf '%s COMPLETED ' $(tr , ' ' <<< "$want"))" ]; then
	tap_ok "running the command again resubmits only tasks $want and gathers ($(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s)"; else
	tap_not_ok "running the command again resubmits only tasks $want" "exit $rc; tasks run: $ran" "$(cat "$T/submit2.out")"; fi
if grep -q "(32 resumed)" "$OUT/slurm-logs/hylo-di-di_neg-${jid2}_$killed.log" &&
	grep -q "(0 resumed)" "$OUT/slurm-logs/hylo-di-di_neg-${jid2}_$lost.log"; then
	tap_ok "the killed task resumed after its 32 complete rows, the torn row dropped"; else
	tap_not_ok "the killed task resumed after its 32 complete rows" "$(cat "$OUT"/slurm-logs/hylo-di-di_neg-"${jid2}"_*.log)"; fi
tap_check "the merged dataset equals the unsharded run's byte for byte" cmp "$OUT/di_neg.csv" "$T/ref/di_neg.csv"
tap_check "the merged .meta equals the unsharded run's" cmp "$OUT/di_neg.csv.meta" "$T/ref/di_neg.csv.meta"
tools/slurm/progress --out "$OUT" --mode di_neg --shards $N > "$T/progress2.out"; rc=$?
if [ $rc -eq 0 ] && grep -q "4/4 tasks done, 0 not started; 256/256 rows (100%)" "$T/progress2.out"; then
	tap_ok "progress: every task done"; else tap_not_ok "progress: every task done" "exit $rc: $(cat "$T/progress2.out")"; fi
timeout 300 "${TRAIN[@]}" --wait > "$T/submit3.out" 2>&1; rc=$?
if [ $rc -eq 0 ] && grep -q "nothing to generate: $OUT/di_neg.csv already holds the 256 rows of this stream" "$T/submit3.out" &&
	! grep -q "submitted array job" "$T/submit3.out" && cmp -s "$OUT/di_neg.csv" "$T/ref/di_neg.csv"; then
	tap_ok "once merged, the same command submits only the gather job, which changes nothing"; else
	tap_not_ok "once complete, the same command submits only the gather job" "exit $rc: $(cat "$T/submit3.out")"; fi
tap_finish
