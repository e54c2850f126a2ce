#!/usr/bin/env bash
# trainer --solve --memory (trainer/memory.hpp; that a neighbour's path
# leads a pair into a cheaper basin: test_memory): the Ambot marine pair of
# row 94 of the memory tests/trainer/memory solved with and without it; a
# dataset directory trainer/datasets/<robot> with a sidecar is the memory
# by default, --memory none turns it off; the row gets its label to the
# last bit (its own path only ties; the label is the solver's on 40
# segments, the path the 20-segment one it was refined from); a missing
# memory and --memory without
# --solve are usage errors (exit 2).
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
TR=$(pwd)/$B/bin/trainer
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

# Row 94 of the memory: its pair solved from its own starts alone, and
# with the memory a dataset directory holds by default.
row94=$(awk -F, 'NR == 2 { print $7 "," $8 "," $9 "," $10, $11 "," $12 "," $13 "," $14, $15 }' tests/trainer/memory/marine.csv)
set -- $row94
A=$1 Z=$2 label=$3
mkdir -p "$T/cwd/trainer/datasets"
cp -r tests/trainer/memory "$T/cwd/trainer/datasets/ambot"
"$TR" --mode marine --robot ambot --solve $A $Z --memory none --json > "$T/none.json" 2> "$T/none.err" &
(cd "$T/cwd" && HYLO_PARAMS_DIR="$OLDPWD/trainer/params" "$TR" --mode marine --robot ambot --solve $A $Z --json) \
  > "$T/mem.json" 2> "$T/mem.err"
wait
field() { sed -n "s/.*\"$2\":\([^,}]*\).*/\1/p" "$1"; }
c0=$(field "$T/none.json" cost_j); c1=$(field "$T/mem.json" cost_j)
if [ "$(field "$T/none.json" converged)" = true ] && [ "$(field "$T/none.json" memory)" = null ] &&
   [ "$(field "$T/none.json" memory_starts)" = 0 ] && [ "$(field "$T/mem.json" converged)" = true ] &&
   [ "$(field "$T/mem.json" memory)" = '"trainer/datasets/ambot/marine.solutions.csv"' ] &&
   [ "$(field "$T/mem.json" memory_starts)" = 2 ] && awk -v a="$c0" -v b="$c1" 'BEGIN { exit !(b <= a) }'; then
  tap_ok "the dataset directory is the default memory: 2 more starts, no dearer ($c0 J, $c1 J); --memory none: none"
else tap_not_ok "the dataset directory is the default memory: 2 more starts, no dearer; --memory none: none" \
  "$(head -c 400 "$T/none.json")" "$(head -c 400 "$T/mem.json")" "$(tail -3 "$T/none.err" "$T/mem.err")"; fi

if [ "$c1" = "$label" ]; then
  tap_ok "a row of the memory solved again: its label to the last bit ($label J)"
else tap_not_ok "a row of the memory solved again: its label to the last bit" "label $label" "$(head -c 400 "$T/mem.json")"; fi

"$TR" --mode marine --robot ambot --solve $A $Z --memory "$T/nowhere" > "$T/out" 2> "$T/err"; rc=$?
if [ $rc -eq 2 ] && grep -q "memory: no $T/nowhere/marine.csv.meta" "$T/err"; then
  tap_ok "a missing memory: exit 2 naming the file"; else tap_not_ok "a missing memory: exit 2 naming the file" "exit $rc" "$(cat "$T/err")"; fi
"$TR" --mode marine --robot ambot --stage gen --samples 1 --out "$T/gen" --memory tests/trainer/memory > "$T/out" 2> "$T/err"; rc=$?
if [ $rc -eq 2 ] && grep -q -- "--memory is for --solve" "$T/err" && [ ! -e "$T/gen" ]; then
  tap_ok "--memory without --solve: exit 2, nothing written"; else tap_not_ok "--memory without --solve: exit 2, nothing written" "exit $rc" "$(cat "$T/err")"; fi
"$TR" --help > "$T/help"
if grep -q -- "--memory DIR" "$T/help" && grep -A5 -- "--memory DIR" "$T/help" | grep -q "default: trainer/datasets/<robot>"; then
  tap_ok "--help describes --memory and its default"; else tap_not_ok "--help describes --memory and its default"; fi
tap_finish
