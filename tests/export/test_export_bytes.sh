#!/usr/bin/env bash
# Exporting the same model twice gives the same bytes, with no date in them;
# the header compiles as strict C99 on its own.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
mkdir -p "$T/a" "$T/b"
"$B/test/export/make_test_model" "$T/a" && "$B/test/export/make_test_model" "$T/b"
tap_check "two exports are byte-identical" cmp "$T/a/testbot_ground.h" "$T/b/testbot_ground.h"
if grep -q -E '20[0-9]{2}-[0-9]{2}-[0-9]{2}' "$T/a/testbot_ground.h"; then
  tap_not_ok "no date in the header"; else tap_ok "no date in the header"; fi
printf '#include "testbot_ground.h"\nint main(void) { return hylo_model_testbot_ground.n_sv > 0 ? 0 : 1; }\n' > "$T/use.c"
tap_check "the header compiles alone under -std=c99 -Wall -Wextra -Werror -pedantic" \
  gcc -std=c99 -Wall -Wextra -Werror -pedantic -Ionboard/include -I"$T/a" -c "$T/use.c" -o "$T/use.o"
tap_finish
