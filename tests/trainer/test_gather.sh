#!/usr/bin/env bash
# The gather step of a sharded dataset (trainer --stage gather, no Slurm):
# a shard run only generates; missing, short and torn shards are named for
# resubmission (exit 1) and shards of another seed, robot file or solver
# setting, or with another shard's rows, are named to move away (exit 2),
# nothing merged; complete shards merge into the unsharded run's file and
# .meta byte for byte, atomically, and an unsharded run resumes it untouched.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
TR=$B/bin/trainer
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

S=48   # 3 shards of 16 rows (one chunk each)
tr_di() { "$TR" --mode di_neg --robot di --quiet --samples $S --seed 3 "$@"; }
gather() { tr_di --stage gather --shards 3 --out "$T/sh" "$@" > "$T/out" 2> "$T/err"; }
expect() {  # NAME CODE NEEDLE...: the last gather's exit code and output lines
	local name=$1 code=$2 rc=$3; shift 3
	local miss=""
	for n in "$@"; do grep -qF -- "$n" "$T/out" || miss="$miss [$n]"; done
	if [ "$rc" -eq "$code" ] && [ -z "$miss" ]; then tap_ok "$name"; else
		tap_not_ok "$name" "exit $rc (want $code); missing:$miss" "$(cat "$T/out" "$T/err" | head -8)"; fi
}
shard() { echo "$T/sh/di_neg.shard-$1-of-3.csv"; }

tr_di --stage gen --jobs 2 --out "$T/ref" > /dev/null
tr_di --shard 1/3 --jobs 2 --out "$T/sh" > "$T/gen1.out" 2>&1; rc=$?
if [ $rc -eq 0 ] && grep -q "^gen di di_neg: 16 samples" "$T/gen1.out" && ! grep -q "^fit" "$T/gen1.out"; then
	tap_ok "--shard K/N without --stage only generates (exit 0)"; else
	tap_not_ok "--shard K/N without --stage only generates (exit 0)" "exit $rc" "$(head -3 "$T/gen1.out")"; fi
cp "$T/ref/di_neg.csv" "$T/ref/di_neg.csv.meta" "$T/sh/"   # a stale unsharded dataset beside the shards
for stage in all fit export repair; do
	tr_di --shard 2/3 --stage $stage --out "$T/sh" > "$T/out" 2> "$T/err"; rc=$?
	if [ $rc -eq 2 ] && grep -q "only generates (--stage gen); gather the N shards with --stage gather --shards N" "$T/err" &&
		[ ! -e "$T/sh/di_neg.fit.json" ] && [ ! -e "$(shard 2)" ]; then
		tap_ok "--shard 2/3 --stage $stage is refused (exit 2), nothing fitted from the stale file"; else
		tap_not_ok "--shard 2/3 --stage $stage is refused (exit 2)" "exit $rc" "$(cat "$T/err")"; fi
done
rm "$T/sh/di_neg.csv" "$T/sh/di_neg.csv.meta"
tr_di --stage gather --out "$T/sh" > /dev/null 2> "$T/err"; rc=$?
if [ $rc -eq 2 ] && grep -q "needs --shards N" "$T/err"; then tap_ok "--stage gather without --shards: exit 2"; else
	tap_not_ok "--stage gather without --shards: exit 2" "exit $rc: $(cat "$T/err")"; fi
tr_di --stage gen --shards 3 --out "$T/sh" > /dev/null 2> "$T/err"; rc=$?
if [ $rc -eq 2 ] && grep -q "is for --stage gather" "$T/err"; then tap_ok "--shards with --stage gen: exit 2"; else
	tap_not_ok "--shards with --stage gen: exit 2" "exit $rc: $(cat "$T/err")"; fi

tr_di --shard 3/3 --jobs 2 --out "$T/sh" > /dev/null
gather; expect "shard 2 missing: named, exit 1" 1 $? "shard 1/3 ok: 16 rows" "shard 2/3 missing: no $(shard 2)" \
	"shard 3/3 ok" "resubmit: --array=2"
tr_di --shard 2/3 --jobs 2 --out "$T/sh" > /dev/null
cp "$(shard 1)" "$T/s1" && cp "$(shard 3)" "$T/s3"
head -c -1 "$T/s3" > "$(shard 3)"                               # cut in its last row
head -n 6 "$T/s1" > "$(shard 1)"                                # the header and 5 rows
gather; expect "a short shard and a torn tail: named with their rows, exit 1" 1 $? \
	"shard 1/3 incomplete: 5 of 16 rows" "shard 3/3 torn: a torn last row (" "bytes) after 15 of 16 rows" \
	"resubmit: --array=1,3"
printf 'index,f0' > "$(shard 1)"
gather; expect "a torn header: named, exit 1" 1 $? "shard 1/3 torn: a torn header (8 bytes)" "resubmit: --array=1,3"
rm "$(shard 1)"
gather; expect "a .meta without its file (killed before a row): 0 rows, exit 1" 1 $? "shard 1/3 incomplete: 0 of 16 rows" \
	"resubmit: --array=1,3"
if [ ! -e "$T/sh/di_neg.csv" ] && [ ! -e "$T/sh/di_neg.csv.meta" ]; then tap_ok "nothing merged while shards are missing"; else
	tap_not_ok "nothing merged while shards are missing"; fi
tr_di --shard 1/3 --jobs 2 --out "$T/sh" > /dev/null && tr_di --shard 3/3 --jobs 2 --out "$T/sh" > "$T/resume3.out"
if grep -q "(15 resumed)" "$T/resume3.out"; then tap_ok "the torn shard's task resumes it after its last complete row"; else
	tap_not_ok "the torn shard's task resumes it after its last complete row" "$(cat "$T/resume3.out")"; fi

# Shards that are not this dataset's: moved in from elsewhere.
mv "$(shard 2)" "$T/s2" && mv "$(shard 2).meta" "$T/s2.meta"
"$TR" --mode di_neg --robot di --quiet --samples $S --seed 4 --shard 2/3 --out "$T/seed4" > /dev/null
cp "$T/seed4/di_neg.shard-2-of-3.csv" "$(shard 2)" && cp "$T/seed4/di_neg.shard-2-of-3.csv.meta" "$(shard 2).meta"
gather; expect "a shard of another seed: named with the seeds, exit 2" 2 $? \
	"shard 2/3 not this stream's: made under other settings (its .meta vs these options): seed: 4 vs seed: 3" \
	"not this dataset's: shards 2; gather with the options they were made with, or move them"
mkdir -p "$T/params" && { cat trainer/params/di.yaml; echo "# another robot file"; } > "$T/params/di.yaml"
HYLO_PARAMS_DIR="$T/params" tr_di --shard 2/3 --out "$T/hash" > /dev/null
cp "$T/hash/di_neg.shard-2-of-3.csv" "$(shard 2)" && cp "$T/hash/di_neg.shard-2-of-3.csv.meta" "$(shard 2).meta"
gather; expect "a shard from another robot file: named by its hash, exit 2" 2 $? "shard 2/3 not this stream's" "params_sha256: "
tr_di --shard 2/3 --segments 10 --out "$T/seg" > /dev/null
cp "$T/seg/di_neg.shard-2-of-3.csv" "$(shard 2)" && cp "$T/seg/di_neg.shard-2-of-3.csv.meta" "$(shard 2).meta"
gather; expect "a shard under other solver settings: named, exit 2" 2 $? "segments: 10 vs segments: 20"
cp "$T/s2.meta" "$(shard 2).meta" && tail -n +2 "$T/ref/di_neg.csv" | sed -n '33,48p' > "$(shard 2)"
gather; expect "shard 3's rows in shard 2's file: the first wrong row named, exit 2" 2 $? \
	"$(shard 2):1: sample 32, expected sample 16"
{ cat "$T/s2"; tail -n 1 "$T/s2"; } > "$(shard 2)"
gather; expect "a row too many: exit 2" 2 $? "$(shard 2):17: more rows than the 16 of shard 2/3"
cp "$T/s2" "$(shard 2)"

cp "$T/ref/di_neg.csv.meta" "$T/sh/di_neg.csv.meta" && echo "seed: 9" >> "$T/sh/di_neg.csv.meta" && touch "$T/sh/di_neg.csv"
gather; rc=$?
if [ $rc -eq 2 ] && grep -q "di_neg.csv exists and was made under other settings" "$T/err" && [ ! -s "$T/sh/di_neg.csv" ]; then
	tap_ok "an unsharded dataset of other settings in --out is not overwritten (exit 2)"; else
	tap_not_ok "an unsharded dataset of other settings in --out is not overwritten (exit 2)" "exit $rc: $(cat "$T/err")"; fi
rm "$T/sh/di_neg.csv" "$T/sh/di_neg.csv.meta"
gather; expect "every shard complete: merged, exit 0" 0 $? "shard 2/3 ok: 16 rows" "merged 3 shards, 48 rows, into $T/sh/di_neg.csv"
tap_check "the merged dataset equals the unsharded run's byte for byte" cmp "$T/sh/di_neg.csv" "$T/ref/di_neg.csv"
tap_check "the merged .meta equals the unsharded run's" cmp "$T/sh/di_neg.csv.meta" "$T/ref/di_neg.csv.meta"
if [ -z "$(find "$T/sh" -name '*.tmp')" ]; then tap_ok "no temporary file left"; else tap_not_ok "no temporary file left"; fi
tr_di --stage gen --out "$T/sh" > "$T/resume.out"
if grep -q "48 samples in .* (48 resumed)" "$T/resume.out" && cmp -s "$T/sh/di_neg.csv" "$T/ref/di_neg.csv"; then
	tap_ok "an unsharded run over the merged dataset resumes all 48 rows and changes nothing"; else
	tap_not_ok "an unsharded run over the merged dataset resumes all 48 rows" "$(cat "$T/resume.out")"; fi
gather; expect "gathering again leaves the dataset as it is" 0 $? "di_neg.csv already holds the 48 rows of this stream; no shard needed"
tr_di --stage gen --samples 60 --out "$T/sh" > /dev/null
cp "$T/sh/di_neg.csv" "$T/longer"
rm "$(shard 2)"
gather; expect "a longer unsharded dataset of the stream is kept, no shard needed" 0 $? "already holds the 48 rows"
tap_check "... byte for byte" cmp "$T/sh/di_neg.csv" "$T/longer"
# A complete dataset labelled under other settings (as the committed ones are) is taken as generation takes it.
mkdir -p "$T/old" && head -n 49 "$T/longer" > "$T/old/di_neg.csv" && sed 's/^blas: .*/blas: another/' "$T/sh/di_neg.csv.meta" > "$T/old/di_neg.csv.meta"
tr_di --stage gather --shards 3 --out "$T/old" > "$T/out" 2> "$T/err"; rc=$?
if [ $rc -eq 0 ] && grep -q "already holds the 48 rows of this stream; no shard needed" "$T/out"; then
	tap_ok "a complete dataset of this stream under other numerics needs no shard (as gen resumes it)"; else
	tap_not_ok "a complete dataset of this stream under other numerics needs no shard" "exit $rc: $(cat "$T/out" "$T/err")"; fi
tr_di --samples 60 --stage gather --shards 3 --out "$T/old" > "$T/out" 2> "$T/err"; rc=$?
if [ $rc -eq 2 ] && grep -q "di_neg.csv exists and was made under other settings (blas: another vs blas: " "$T/err"; then
	tap_ok "... but 60 rows of it are refused before any shard is read (exit 2, naming the line)"; else
	tap_not_ok "... but 60 rows of it are refused before any shard is read" "exit $rc: $(cat "$T/out" "$T/err")"; fi
tap_finish
