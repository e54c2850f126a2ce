#!/usr/bin/env bash
# The SVR evaluator's run-time paths give the same bits: the reference plans
# (tools/cross/plan_digest.c, every committed model) of the normal build,
# which takes the AVX2 clones on a CPU that has AVX2, equal those of a build
# without the clones (SSE2 only). make cross-test compares aarch64 the same way.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
a=$("$B/cross/plan_digest" 2>&1); ra=$?
b=$("$B/cross/plan_digest_sse2" 2>&1); rb=$?
if [ $ra -eq 0 ] && [ $rb -eq 0 ] && [ "$(echo "$a" | wc -l)" -ge 9 ]; then
  tap_ok "both builds plan every reference request"; else
  tap_not_ok "both builds plan every reference request" "exit $ra / $rb"; fi
if [ "$a" = "$b" ]; then
  tap_ok "the plans are bit-identical with and without the AVX2 clones"; else
  tap_not_ok "the plans are bit-identical with and without the AVX2 clones" "$(diff <(echo "$a") <(echo "$b") | head -5)"; fi
if grep -q avx2 /proc/cpuinfo; then
  tap_ok "this CPU has AVX2, so the normal build took the AVX2 path"; else
  tap_skip "the normal build took the AVX2 path" "this CPU has no AVX2: both builds took the SSE2 path"; fi
tap_finish
