# Barriers for the node tests, so that a loaded machine waits longer instead
# of losing a message or a signal to a fixed sleep.

# poll WHAT CMD...: until CMD succeeds, every 0.1 s for at most 60 s; else
# says "WHAT after 60 s" and fails.
poll() {
  local what=$1 i
  shift
  for i in $(seq 600); do
    "$@" && return 0
    sleep 0.1
  done
  echo "$what after 60 s" >&2
  return 1
}

# wait_receivers N [PORT]: until N sockets are bound to the UDP port of the
# LCM multicast URL (one per subscribed process: LCM binds the port when a
# process first subscribes). Run inside the test's network namespace, where
# only the test's own processes have sockets.
receivers_at_least() { [ "$(ss -Huln "sport = :$2" | wc -l)" -ge "$1" ]; }
wait_receivers() {
  poll "wait_receivers: fewer than $1 receivers on UDP port ${2:-7667}" receivers_at_least "$1" "${2:-7667}"
}

# wait_catching PID: until process PID has its SIGINT and SIGTERM handlers
# installed (bits 2 and 15 of SigCgt in /proc/PID/status).
catches_int_and_term() {
  local mask
  mask=$(sed -n 's/^SigCgt:[[:space:]]*//p' "/proc/$1/status" 2>/dev/null)
  [ -n "$mask" ] && [ $(( 0x$mask & 0x4002 )) -eq $(( 0x4002 )) ]
}
wait_catching() { poll "wait_catching: process $1 does not catch SIGINT and SIGTERM" catches_int_and_term "$1"; }

# wait_line FILE REGEX: until a line of FILE matches REGEX (grep -E).
wait_line() { poll "wait_line: no line matching '$2' in $1" grep -Eqs "$2" "$1"; }

# wait_plans LISTEN LOG N: until the lcm-logger log LOG holds N plans, read
# back with the hylo-listen binary LISTEN.
plans_at_least() { [ "$("$1" --lcm-url "file://$2?speed=0" 2>/dev/null | grep -c '^plan ')" -ge "$3" ]; }
wait_plans() { poll "wait_plans: fewer than $3 plans in $2" plans_at_least "$1" "$2" "$3"; }
