#!/usr/bin/env bash
# The documentation stays true to the repository:
#  - tools/check-docs: no file refers to a path outside the repository or to
#    a document that is not in it; every link, anchor and `path` in the
#    Markdown documents resolves; README's benchmark table is
#    docs/benchmarks.md's. Its checks are shown to catch each kind of fault.
#  - tools/provenance check: no committed picture or results file is older
#    than the models, robot files or scenes it was made from. Shown to catch
#    a refitted model and a changed scene, and to ignore what does not change
#    a picture (comments, an envelope, a scene's description).
#  - the README's five-minute tour runs as written (all but its smoothing
#    and training steps, which tests/trainer/ covers), and the tiny program
#    it links builds as strict C99 and plans.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

tap_check "tools/check-docs: documents, links and citations resolve inside the repository" tools/check-docs
tap_check "tools/provenance check: every picture and results file is as new as its inputs" tools/provenance check

# check-docs on a small tree with one fault of each kind.
mkdir -p "$T/docs/tree/tools" "$T/docs/tree/docs" "$T/docs/tree/mk" "$T/docs/tree/trainer"
D=$T/docs/tree
cp tools/check-docs "$D/tools/"
table='<!-- benchmarks:begin -->
| a | b |
<!-- benchmarks:end -->'
printf '# Title\n\n## A section\n\n%s\n' "$table" > "$D/docs/benchmarks.md"
printf '# R\n\nSee [the section](docs/benchmarks.md#a-section) and `docs/benchmarks.md`.\n\n%s\n' "$table" > "$D/README.md"
printf '// docs/benchmarks.md\nint x;\n' > "$D/trainer/ok.cpp"
if (cd "$D" && tools/check-docs > "$T/out"); then tap_ok "check-docs passes a clean tree"; else
  tap_not_ok "check-docs passes a clean tree" "$(cat "$T/out")"; fi
expect_fault() {  # NAME NEEDLE: after the caller broke the tree
  if (cd "$D" && tools/check-docs > "$T/out"); then tap_not_ok "$1" "check-docs passed"; elif grep -q -- "$2" "$T/out"; then
    tap_ok "$1"; else tap_not_ok "$1" "$(cat "$T/out")"; fi
}
cp "$D/README.md" "$T/readme"
gone=missing   # (named in pieces, so that this file passes check-docs itself)
sed -i "s|docs/benchmarks.md#a-section|docs/$gone.md|" "$D/README.md"
expect_fault "check-docs: a link to a missing document" "README.md:3: link to docs/$gone.md"
cp "$T/readme" "$D/README.md"; sed -i 's|#a-section|#no-such-heading|' "$D/README.md"
expect_fault "check-docs: a link to a missing heading" "no heading #no-such-heading"
cp "$T/readme" "$D/README.md"; sed -i 's|`docs/benchmarks.md`|`docs/gone/`|' "$D/README.md"
expect_fault "check-docs: a path in backticks that does not exist" '`docs/gone/` does not exist'
cp "$T/readme" "$D/README.md"; sed -i 's/| a | b |/| a | c |/' "$D/README.md"
expect_fault "check-docs: README's benchmark table differs from docs/benchmarks.md's" "benchmark table differs"
cp "$T/readme" "$D/README.md"
printf '// the spec: models.md section 7\nint y;\n' > "$D/trainer/bad.cpp"
expect_fault "check-docs: code citing a document that is not in the repository" "trainer/bad.cpp:1: names models.md"
rm "$D/trainer/bad.cpp"
printf '/* the picture: docs/%s.png */\n' "$gone" > "$D/trainer/bad.c"
expect_fault "check-docs: code naming a docs/ file that does not exist" "trainer/bad.c:1: names docs/$gone.png"
rm "$D/trainer/bad.c"
printf '# Ipopt quirks: ../%s/deps.md\n' "sha""red" > "$D/mk/bad.mk"
expect_fault "check-docs: a reference to the shared folder" "mk/bad.mk:1: refers to a path outside"
rm "$D/mk/bad.mk"

# provenance on a copy of the inputs and the manifest.
P=$T/prov
mkdir -p "$P/tools" "$P/onboard" "$P/trainer"
cp tools/provenance "$P/tools/"
cp -r docs "$P/docs"
cp -r scenes "$P/scenes"
cp -r onboard/models "$P/onboard/models"
cp -r trainer/params "$P/trainer/params"
prov() { "$P/tools/provenance" "$@" > "$T/out" 2>&1; }
if prov check; then tap_ok "provenance: a copy checks clean"; else tap_not_ok "provenance: a copy checks clean" "$(cat "$T/out")"; fi
# An envelope re-export, a comment and a scene's prose change no picture.
# edit FILE ARRAY: adds 1 to the first number after the line that opens ARRAY.
edit() {
  python3 - "$1" "$2" <<'PY'
import re, sys
path, array = sys.argv[1], sys.argv[2]
lines = open(path).read().split("\n")
k = next(i for i, l in enumerate(lines) if array + "[" in l and l.endswith("= {"))
lines[k + 1] = re.sub(r"^\t(-?[0-9.e+-]+),", lambda m: "\t%r," % (float(m.group(1)) + 1), lines[k + 1])
open(path, "w").write("\n".join(lines))
PY
}
edit "$P/onboard/models/ambot_ground.h" hylo_model_ambot_ground_envelope_value
cmp -s onboard/models/ambot_ground.h "$P/onboard/models/ambot_ground.h" && tap_not_ok "the envelope edit changed the header"
sed -i '1s/^/# a comment\n/' "$P/scenes/river_crossing.yaml" "$P/trainer/params/ambot.yaml"
sed -i 's/^  The hybrid double integrator/  The double integrator/' "$P/scenes/di.yaml"
if prov check; then tap_ok "provenance: an envelope, comments and a description change nothing"; else
  tap_not_ok "provenance: an envelope, comments and a description change nothing" "$(cat "$T/out")"; fi
# A refitted model: every picture and result drawn with it is stale.
edit "$P/onboard/models/ambot_marine.h" hylo_model_ambot_marine_coef
cmp -s onboard/models/ambot_marine.h "$P/onboard/models/ambot_marine.h" && tap_not_ok "the coefficient edit changed the header"
if ! prov check && grep -q "^docs/pictures/river_crossing.png: older than onboard/models/ambot_marine.h" "$T/out" &&
   grep -q "^docs/results/ambot.json: older than onboard/models/ambot_marine.h" "$T/out" &&
   grep -q "^docs/models/ambot_marine_contour.png: older than" "$T/out" &&
   ! grep -q "^docs/pictures/chasm_030.png" "$T/out"; then
  tap_ok "provenance: a refitted model makes its pictures and results stale, no others"; else
  tap_not_ok "provenance: a refitted model makes its pictures and results stale, no others" "$(cat "$T/out")"; fi
cp onboard/models/ambot_marine.h "$P/onboard/models/"
# A changed map.
sed -i 's/resolution_m: 0.5/resolution_m: 0.25/' "$P/scenes/chasm_050.yaml"
cmp -s scenes/chasm_050.yaml "$P/scenes/chasm_050.yaml" && tap_not_ok "the scene edit changed the scene"
if ! prov check && grep -q "^docs/pictures/chasm_050.png: older than scenes/chasm_050.yaml (regenerate it: make pictures)" "$T/out"; then
  tap_ok "provenance: a changed scene makes its picture stale"; else
  tap_not_ok "provenance: a changed scene makes its picture stale" "$(cat "$T/out")"; fi
cp scenes/chasm_050.yaml "$P/scenes/"
cp "$P/docs/pictures/di.png" "$P/docs/pictures/new_scene.png"
if ! prov check && grep -q "^docs/pictures/new_scene.png: no record" "$T/out"; then
  tap_ok "provenance: a picture without a record fails"; else
  tap_not_ok "provenance: a picture without a record fails" "$(cat "$T/out")"; fi

# The README's tour, as written (from the repository root, into build/tour).
if [ "$B" != build ]; then
  tap_skip "the README's tour runs as written" "BUILD=$B: the README's commands use build/"
else
  python3 - README.md > "$T/tour.sh" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
tour = re.search(r"^## A five-minute tour\n(.*?)^## ", text, re.S | re.M).group(1)
lines, cmd = [], ""
for line in tour.splitlines():
    if not line.startswith("    "):
        continue
    cmd += line.strip()
    if cmd.endswith("\\"):
        cmd = cmd[:-1] + " "
        continue
    # Smoothing and training are tested in tests/trainer/; here the rest.
    if not re.search(r"hylo-smooth|traj\.log|planned\.log|--samples|di_di_neg\.h", cmd):
        lines.append(cmd)
    cmd = ""
print("set -e")
print("\n".join(lines))
PY
  if [ "$(grep -c build/bin "$T/tour.sh")" -ge 6 ] && bash "$T/tour.sh" > "$T/tour.out" 2>&1 &&
     [ -s build/tour/island.png ] && grep -q "plan: .* J over" "$T/tour.out"; then
    tap_ok "the README's tour runs as written ($(grep -c . "$T/tour.sh") commands)"; else
    tap_not_ok "the README's tour runs as written" "$(tail -15 "$T/tour.out")"; fi
fi
gcc -std=c99 -Wall -Wextra -Werror -pedantic -Ionboard/include docs/examples/tiny_planner.c "$B/lib/libhylo.a" -lm \
  -o "$T/tiny" 2> "$T/tiny.err" && "$T/tiny" > "$T/tiny.out"
if [ $? -eq 0 ] && grep -q "^workspace .* MB; plan: .* J over .* waypoints" "$T/tiny.out"; then
  tap_ok "docs/examples/tiny_planner.c builds as strict C99 and plans"; else
  tap_not_ok "docs/examples/tiny_planner.c builds as strict C99 and plans" "$(cat "$T/tiny.err" "$T/tiny.out" | head -5)"; fi
tap_finish
