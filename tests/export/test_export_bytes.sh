#!/usr/bin/env bash
# Exporting the same model twice gives the same bytes, with no date in them,
# also when its envelope is computed on 1 and on 2 threads; the header
# compiles as strict C99 on its own, and not against a library that reads
# another model format.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# The build's export (make_test_model OUT_DIR: the envelope on 1 thread) is
# the first one.
mkdir -p "$T/a" "$T/b"
cp "$B/gen/test-models/testbot_ground.h" "$T/a/" && "$B/test/export/make_test_model" "$T/b" 2
tap_check "two exports (the envelope on 1 and on 2 threads) are byte-identical" \
  cmp "$T/a/testbot_ground.h" "$T/b/testbot_ground.h"
if grep -q '^static const hylo_svr_envelope hylo_model_testbot_ground_envelope = {$' "$T/a/testbot_ground.h" &&
   grep -q '^	.envelope = &hylo_model_testbot_ground_envelope,$' "$T/a/testbot_ground.h" &&
   grep -q '^ \* envelope: 61 x 16 x 6 cells, margin 0.001, worst sampled shortfall ' "$T/a/testbot_ground.h"; then
  tap_ok "the header carries the envelope (16 turn cells), its model field and its provenance line"; else
  tap_not_ok "the header carries the envelope (16 turn cells), its model field and its provenance line"; fi
if grep -q -E '20[0-9]{2}-[0-9]{2}-[0-9]{2}' "$T/a/testbot_ground.h"; then
  tap_not_ok "no date in the header"; else tap_ok "no date in the header"; fi
printf '#include "testbot_ground.h"\nint main(void) { return hylo_model_testbot_ground.n_sv > 0 ? 0 : 1; }\n' > "$T/use.c"
tap_check "the header compiles alone under -std=c99 -Wall -Wextra -Werror -pedantic" \
  gcc -std=c99 -Wall -Wextra -Werror -pedantic -Ionboard/include -I"$T/a" -c "$T/use.c" -o "$T/use.o"
sed 's/^#define HYLO_MODEL_TESTBOT_GROUND_FORMAT_VERSION .*/#define HYLO_MODEL_TESTBOT_GROUND_FORMAT_VERSION 999/' \
  "$T/a/testbot_ground.h" > "$T/use_format.h"
printf '#include "use_format.h"\nint main(void) { return 0; }\n' > "$T/use_format.c"
if ! gcc -std=c99 -Ionboard/include -I"$T" -c "$T/use_format.c" -o "$T/use_format.o" 2> "$T/format.err" &&
   grep -q 'error: #error "testbot_ground.h is model format .*HYLO_MODEL_FORMAT_VERSION' "$T/format.err"; then
  tap_ok "a header of another model format stops the compilation, naming HYLO_MODEL_FORMAT_VERSION"; else
  tap_not_ok "a header of another model format stops the compilation, naming HYLO_MODEL_FORMAT_VERSION" "$(head -3 "$T/format.err")"; fi
tap_finish
