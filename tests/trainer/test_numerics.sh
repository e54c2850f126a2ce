#!/usr/bin/env bash
# Labels do not depend on the CPU (trainer/numerics.hpp): the trainer loads
# the reference BLAS and LAPACK and pins libm; it refuses another BLAS; its
# solutions are byte for byte the same under every OpenBLAS kernel setting
# (which it must ignore) and with the user's own glibc.cpu.hwcaps mask (a
# smaller CPU emulated); test_collocation passes under every forced kernel
# setting, printing the same labels to the last digit (make test runs it
# under the machine's own too);
# a dataset labelled under other numerics is not extended. Prints TAP.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
TR=$B/bin/trainer
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

# (a) What is loaded.
"$TR" --version > "$T/version"; rc=$?
if [ "$rc" -eq 0 ] && grep -q "^blas: .*/blas/libblas\.so.* (reference)$" "$T/version" &&
   grep -q "^lapack: .*/lapack/liblapack\.so.* (reference)$" "$T/version" &&
   grep -q "^ipopt: " "$T/version" && grep -q "^mumps: " "$T/version" &&
   { [ "$(uname -m)" != x86_64 ] || grep -q "^libm: glibc .*, hwcaps -AVX2,-FMA,-FMA4$" "$T/version"; } &&
   ! grep -qi openblas "$T/version"; then
  tap_ok "--version names the reference BLAS and LAPACK and the libm pin"
else tap_not_ok "--version names the reference BLAS and LAPACK and the libm pin" "$(cat "$T/version")"; fi
sed 's/^/# /' "$T/version"

# The maps of a solving trainer: the reference BLAS, no OpenBLAS. Read
# once the loader has mapped Ipopt, BLAS and LAPACK (a process caught
# mid-load, as after the re-execution, has only some of them).
"$TR" --mode flight --robot drivocopter --solve 0,0,0,0,0,0 3,1,0.5,0,0,0 > /dev/null &
pid=$!
maps=""
for _ in $(seq 1 200); do
  maps=$(cat "/proc/$pid/maps" 2>/dev/null)
  [[ $maps == *libipopt* && $maps == *libblas* && $maps == *liblapack* ]] && break
  sleep 0.05
done
wait $pid
if [[ $maps == */blas/libblas.so* && $maps != *openblas* ]]; then
  tap_ok "a solving trainer maps the reference BLAS and no OpenBLAS (/proc/PID/maps)"
else tap_not_ok "a solving trainer maps the reference BLAS and no OpenBLAS (/proc/PID/maps)" \
  "$(echo "$maps" | grep -i -E 'blas|lapack|ipopt' | awk '{print $6}' | sort -u)"; fi

# Another BLAS is refused, naming it.
openblas=$(ls /usr/lib/*/libopenblas.so.0 2>/dev/null | head -1)
if [ -n "$openblas" ]; then
  LD_PRELOAD=$openblas "$TR" --mode di_neg --robot di --solve -0.5,0 -0.3,0 > "$T/out" 2> "$T/err"; rc=$?
  if [ "$rc" -eq 1 ] && grep -q "other than the reference one is loaded (.*openblas" "$T/err" && [ ! -s "$T/out" ]; then
    tap_ok "with OpenBLAS preloaded the trainer refuses to run (exit 1), naming it"
  else tap_not_ok "with OpenBLAS preloaded the trainer refuses to run (exit 1), naming it" "exit $rc" "$(cat "$T/err")"; fi
else
  tap_skip "with OpenBLAS preloaded the trainer refuses to run" "no OpenBLAS installed"
fi

# The re-execution happens once: if the mask does not take, it says so.
if grep -q -w -E 'avx2|fma' /proc/cpuinfo 2>/dev/null && [ "$(uname -m)" = x86_64 ]; then
  env -u GLIBC_TUNABLES HYLO_NUMERICS_REEXEC=1 "$TR" --version > /dev/null 2> "$T/err"; rc=$?
  if [ "$rc" -eq 1 ] && grep -q "still active" "$T/err"; then
    tap_ok "a re-executed trainer whose libm is still unpinned refuses to run"
  else tap_not_ok "a re-executed trainer whose libm is still unpinned refuses to run" "exit $rc" "$(cat "$T/err")"; fi
else
  tap_skip "a re-executed trainer whose libm is still unpinned refuses to run" "no AVX2/FMA on this CPU"
fi

# (b) The same bytes under every kernel setting and hwcaps mask. Pairs: the
# double integrator, a 2 m Ambot marine edge (a 3 m one with a turn took 4
# times its CPU), a short Drivocopter ground edge (Ambot ground with the
# goal behind is test_collocation's, in (c)).
solves() {
  "$TR" --mode di_neg --robot di --solve -0.5,0 -0.3,0 --json &&
  "$TR" --mode marine --robot ambot --solve 0,0,0.5,0 2,0.2,0.6,0.1 --json &&
  "$TR" --mode ground --robot drivocopter --solve 0,0,0.5,0 1.5,-0.5,0.5,-0.3 --json
}
# setting NAME: runs the solves with that kernel setting (default: the
# machine's environment without OPENBLAS_CORETYPE) and tunables (-: unset).
setting() {
  local kernel=$1 tunables=$2 env_args=(env -u OPENBLAS_CORETYPE -u GLIBC_TUNABLES)
  [ "$kernel" = default ] || env_args+=("OPENBLAS_CORETYPE=$kernel")
  [ "$tunables" = - ] || env_args+=("GLIBC_TUNABLES=$tunables")
  TR=$TR "${env_args[@]}" bash -c "$(declare -f solves); solves" 2> "$T/$kernel.$3.err" |
    sed 's/,"solve_s":[0-9.e+-]*//' > "$T/$kernel.$3.json"
}
# Every kernel setting, and the hwcaps mask (which picks libm's variants,
# not BLAS kernels) with the machine's own; two settings at a time.
names=(default.plain Prescott.plain Nehalem.plain Haswell.plain SkylakeX.plain default.noavx512)
setting default - plain & setting Prescott - plain; wait
setting Nehalem - plain & setting Haswell - plain; wait
setting SkylakeX - plain & setting default glibc.cpu.hwcaps=-AVX512F noavx512; wait
ref=$T/${names[0]}.json
differ=""
for n in "${names[@]}"; do cmp -s "$ref" "$T/$n.json" || differ+="$n "; done
if [ "$(wc -l < "$ref")" -eq 3 ] && [ -z "$differ" ]; then
  tap_ok "3 BVPs: byte-identical JSON (solve_s aside) under OPENBLAS_CORETYPE default, Prescott, Nehalem, Haswell, SkylakeX, and glibc.cpu.hwcaps=-AVX512F"
else tap_not_ok "3 BVPs: byte-identical JSON (solve_s aside) under every kernel setting and hwcaps mask" \
  "differ from ${names[0]}: ${differ:-none}; $(wc -l < "$ref") results" "$(cat "$T/${names[0]}.err" | head -5)"; fi
python3 -c 'import json,sys
for l in open(sys.argv[1]): d=json.loads(l); print("# %s %s: %s, %.6f J" % (d["robot"], d["mode"], d["status"], d["cost_j"]))' "$ref"

# (c) test_collocation under every forced kernel setting, two at a time
# (under the machine's own, make test runs it on its own line): it passes,
# and its output, which prints its labels to the last digit (Ambot ground
# with the goal behind among them), is the same bytes under each.
collocation() {
  OPENBLAS_CORETYPE=$1 "$B/test/trainer/test_collocation" > "$T/tc.$1" 2>&1 || : > "$T/tc.$1.failed"
}
collocation Prescott & collocation Nehalem; wait
collocation Haswell & collocation SkylakeX; wait
failed=""
for kernel in Prescott Nehalem Haswell SkylakeX; do
  [ -e "$T/tc.$kernel.failed" ] && failed+="$kernel "
done
if [ -z "$failed" ]; then tap_ok "test_collocation passes under OPENBLAS_CORETYPE Prescott, Nehalem, Haswell, SkylakeX"
else tap_not_ok "test_collocation passes under every kernel setting" "fails under: $failed" \
  "$(grep '^not ok' "$T/tc.${failed%% *}" | head -3)"; fi
differ=""
for kernel in Nehalem Haswell SkylakeX; do cmp -s "$T/tc.Prescott" "$T/tc.$kernel" || differ+="$kernel "; done
if [ -s "$T/tc.Prescott" ] && [ -z "$differ" ]; then
  tap_ok "test_collocation prints the same bytes, labels to the last digit, under Prescott, Nehalem, Haswell, SkylakeX"
else tap_not_ok "test_collocation prints the same bytes under every kernel setting" "differ from Prescott: ${differ:-none}" \
  "$(diff "$T/tc.Prescott" "$T/tc.${differ%% *}" | head -4)"; fi
grep "^# .* J" "$T/tc.Prescott"

# (d) A dataset labelled under other numerics is not extended, and the
# refusal names the line; a run that asks for no new row leaves it alone.
gen() { "$TR" --mode di_neg --robot di --stage gen --quiet --seed 7 --jobs 2 --out "$T/ds" "$@"; }
gen --samples 4 > /dev/null
sed -i 's|^blas: .*|blas: /usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3|' "$T/ds/di_neg.csv.meta"
cp "$T/ds/di_neg.csv" "$T/before.csv"
gen --samples 8 > /dev/null 2> "$T/err"; rc=$?
if [ "$rc" -eq 1 ] &&
   grep -q "di_neg.csv was made under other settings: blas: /usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3 vs blas: .*(reference); regenerate it into another --out directory" "$T/err" &&
   cmp -s "$T/before.csv" "$T/ds/di_neg.csv"; then
  tap_ok "extending a dataset whose .meta names another BLAS is refused, old vs new line named"
else tap_not_ok "extending a dataset whose .meta names another BLAS is refused, old vs new line named" "exit $rc" "$(cat "$T/err")"; fi
gen --samples 4 > /dev/null 2>&1; rc=$?
if [ "$rc" -eq 0 ] && cmp -s "$T/before.csv" "$T/ds/di_neg.csv"; then
  tap_ok "a run that needs no new row of such a dataset leaves it as it is (exit 0)"
else tap_not_ok "a run that needs no new row of such a dataset leaves it as it is (exit 0)" "exit $rc"; fi
tap_finish
