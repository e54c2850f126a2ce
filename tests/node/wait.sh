# Barriers for the node tests, so that a loaded machine waits longer instead
# of losing a message or a signal to a fixed sleep.

# wait_receivers N [PORT]: until N sockets are bound to the UDP port of the
# LCM multicast URL (one per subscribed process: LCM binds the port when a
# process first subscribes), for at most 60 s. Run inside the test's network
# namespace, where only the test's own processes have sockets.
wait_receivers() {
  local i
  for i in $(seq 600); do
    [ "$(ss -Huln "sport = :${2:-7667}" | wc -l)" -ge "$1" ] && return 0
    sleep 0.1
  done
  echo "wait_receivers: fewer than $1 receivers on port ${2:-7667} after 60 s" >&2
  return 1
}

# wait_catching PID: until process PID has its SIGINT and SIGTERM handlers
# installed (bits 2 and 15 of SigCgt in /proc/PID/status), for at most 60 s.
wait_catching() {
  local i mask
  for i in $(seq 600); do
    mask=$(sed -n 's/^SigCgt:[[:space:]]*//p' "/proc/$1/status" 2>/dev/null)
    [ -n "$mask" ] && [ $(( 0x$mask & 0x4002 )) -eq $(( 0x4002 )) ] && return 0
    sleep 0.1
  done
  echo "wait_catching: process $1 does not catch SIGINT and SIGTERM after 60 s" >&2
  return 1
}

# wait_line FILE REGEX: until a line of FILE matches REGEX (grep -E), for at
# most 60 s.
wait_line() {
  local i
  for i in $(seq 600); do
    grep -Eq "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
  done
  echo "wait_line: no line matching '$2' in $1 after 60 s" >&2
  return 1
}

# wait_plans LISTEN LOG N: until the lcm-logger log LOG holds N plans, read
# back with the hylo-listen binary LISTEN, for at most 60 s.
wait_plans() {
  local i
  for i in $(seq 600); do
    [ "$("$1" --lcm-url "file://$2?speed=0" 2>/dev/null | grep -c '^plan ')" -ge "$3" ] && return 0
    sleep 0.1
  done
  echo "wait_plans: fewer than $3 plans in $2 after 60 s" >&2
  return 1
}
