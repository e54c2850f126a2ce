# TAP helpers for shell tests (sourced). Each check prints "ok N - name" or
# "not ok N - name" with the reason as "# " lines; finish prints the plan.
TAP_N=0
TAP_FAILED=0

tap_ok() { TAP_N=$((TAP_N + 1)); echo "ok $TAP_N - $1"; }
tap_not_ok() {
  TAP_N=$((TAP_N + 1)); TAP_FAILED=$((TAP_FAILED + 1))
  echo "not ok $TAP_N - $1"
  shift
  for line in "$@"; do echo "# $line"; done
}
tap_skip() { TAP_N=$((TAP_N + 1)); echo "ok $TAP_N - $1 # SKIP $2"; }

# tap_check NAME CMD...: runs CMD, ok when it exits 0; shows its output otherwise.
tap_check() {
  local name=$1; shift
  local out
  if out=$("$@" 2>&1); then tap_ok "$name"; else tap_not_ok "$name" "command: $*" "$(echo "$out" | tail -15)"; fi
}

# tap_verdict FILE WHAT NAME: ok when FILE has a line "WHAT True ...", as a
# test's Python check prints one per verdict; otherwise not ok, showing that
# line (or, with none, the whole file: the check's traceback).
tap_verdict() {
  local line; line=$(grep "^$2 " "$1")
  if [ "${line#"$2 True"}" != "$line" ]; then tap_ok "$3"; else tap_not_ok "$3" "${line:-$(cat "$1")}"; fi
}

tap_finish() { echo "1..$TAP_N"; [ "$TAP_FAILED" -eq 0 ]; }

# tap_need_netns NAME...: where no network namespace can be created, reports
# the named checks as skipped (never as passed) and ends the test.
tap_need_netns() {
  unshare --net true 2>/dev/null && return 0
  local n
  for n in "$@"; do tap_skip "$n" "cannot create a network namespace here"; done
  tap_finish; exit
}
