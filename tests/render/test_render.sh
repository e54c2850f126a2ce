#!/usr/bin/env bash
# hylo-render and hylo-pngdiff: determinism, one golden image per view,
# pictures that would fail if they were wrong, and bad input.
#   phase  di.yaml planned by the node with the committed DI models (one plan,
#          as top: --alternatives 1)
#   top    tests/node/synthetic.yaml planned with the synthetic robot, with a
#          drawn (fake) trajectory for the robot outlines
#   3d     chasm_030.yaml with a drawn drive-fly-drive plan (fake_traj chasm)
#   top_alternatives  river_crossing.yaml planned by the node with its
#          alternatives (--alternatives 3: three mode sequences)
#   3d_alternatives   chasm_030.yaml planned likewise (two mode sequences)
# UPDATE_GOLDENS=1 (make update-goldens) rewrites tests/render/golden/.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
RENDER=$B/bin/hylo-render
RENDER_S=$B/test/render/hylo-render-synthetic
DIFF=$B/bin/hylo-pngdiff
FAKE=$B/test/render/fake_traj
GOLD=tests/render/golden
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

scene_log() { "$B/bin/hylo-scene" "$@"; }
scene_log scenes/di.yaml --goal --alternatives 1 --lcm-url "file://$T/di.in.log?mode=w"
"$B/bin/hylo-planner" --lcm-url "file://$T/di.in.log?speed=0" \
  --out-url "file://$T/di.plan.log?mode=w" 2>/dev/null
scene_log tests/node/synthetic.yaml --goal --alternatives 1 --lcm-url "file://$T/syn.in.log?mode=w"
"$B/test/node/hylo-planner-synthetic" --lcm-url "file://$T/syn.in.log?speed=0" \
  --out-url "file://$T/syn.plan.log?mode=w" 2>/dev/null
"$FAKE" traj "$T/syn.traj.log" "$T/syn.plan.log"
scene_log scenes/chasm_030.yaml --lcm-url "file://$T/chasm.in.log?mode=w"
"$FAKE" chasm "$T/chasm.plan.log" 130
CAMERA=$("$B/bin/hylo-scene" scenes/chasm_030.yaml --print-camera)
for s in river_crossing chasm_030; do
  scene_log scenes/$s.yaml --goal --alternatives 3 --lcm-url "file://$T/$s.alt.in.log?mode=w"
  "$B/bin/hylo-planner" --lcm-url "file://$T/$s.alt.in.log?speed=0" \
    --out-url "file://$T/$s.alt.plan.log?mode=w" 2>/dev/null
done

render_phase() { "$RENDER" --quiet --log "$T/di.in.log" --log "$T/di.plan.log" --edges "$@"; }
render_top() { "$RENDER_S" --quiet --log "$T/syn.in.log" --log "$T/syn.plan.log" --log "$T/syn.traj.log" "$@"; }
render_3d() { "$RENDER" --quiet --log "$T/chasm.in.log" --log "$T/chasm.plan.log" --camera "$CAMERA" "$@"; }
render_top_alternatives() {
  "$RENDER" --quiet --log "$T/river_crossing.alt.in.log" --log "$T/river_crossing.alt.plan.log" \
    --no-nodes "$@"
}
render_3d_alternatives() {
  "$RENDER" --quiet --log "$T/chasm_030.alt.in.log" --log "$T/chasm_030.alt.plan.log" \
    --no-nodes --camera "$CAMERA" "$@"
}

# Determinism and goldens, one per view.
for view in phase top 3d top_alternatives 3d_alternatives; do
  "render_$view" --out "$T/$view.a.png" && "render_$view" --out "$T/$view.b.png"
  if cmp -s "$T/$view.a.png" "$T/$view.b.png"; then tap_ok "$view view: same inputs, same bytes"
  else tap_not_ok "$view view: same inputs, same bytes"; fi
  if [ "${UPDATE_GOLDENS:-0}" = 1 ]; then mkdir -p "$GOLD" && cp "$T/$view.a.png" "$GOLD/$view.png"; fi
  tap_check "$view view matches its golden image" \
    "$DIFF" "$T/$view.a.png" "$GOLD/$view.png" --diff "$T/$view.diff.png"
done
render_phase --view phase --out "$T/phase.c.png"
render_phase --view top --out "$T/phase.d.png"
if cmp -s "$T/phase.a.png" "$T/phase.c.png" && ! cmp -s "$T/phase.a.png" "$T/phase.d.png"; then
  tap_ok "the view follows the robot (di: phase) unless --view says otherwise"
else tap_not_ok "the view follows the robot (di: phase) unless --view says otherwise"; fi

# A changed plan (another sampling seed) fails the golden comparison, and
# the comparator says where and writes a diff image.
scene_log tests/node/synthetic.yaml --goal --alternatives 1 --seed 11 --lcm-url "file://$T/syn11.in.log?mode=w"
"$B/test/node/hylo-planner-synthetic" --lcm-url "file://$T/syn11.in.log?speed=0" \
  --out-url "file://$T/syn11.plan.log?mode=w" 2>/dev/null
"$RENDER_S" --quiet --log "$T/syn11.in.log" --log "$T/syn11.plan.log" --log "$T/syn.traj.log" \
  --out "$T/top11.png"
out=$("$DIFF" "$T/top11.png" "$GOLD/top.png" --diff "$T/top11.diff.png"); rc=$?
if [ $rc -eq 1 ] && [ -s "$T/top11.diff.png" ] && echo "$out" | grep -q "differ by more than"; then
  tap_ok "a changed plan fails the golden comparison, with a diff image"
else tap_not_ok "a changed plan fails the golden comparison, with a diff image" "exit $rc" "$out"; fi

# With and without the path differ exactly along the path: the mask of
# where the path must be is computed from the plan's waypoints by
# png_tools.py, not by the renderer.
W=480; H=320
opts=(--no-annotations --no-nodes --width $W --height $H)
"$RENDER_S" --quiet --log "$T/syn.in.log" --log "$T/syn.plan.log" "${opts[@]}" --out "$T/with.png"
"$RENDER_S" --quiet --log "$T/syn.in.log" --log "$T/syn.plan.log" "${opts[@]}" --no-path --out "$T/without.png"
"$B/bin/hylo-listen" --lcm-url "file://$T/syn.plan.log?speed=0" --json > "$T/syn.plans.jsonl"
python3 tests/render/png_tools.py path-mask "$T/syn.plans.jsonl" $W $H 30 20 0 0 "$T/mask.png"
tap_check "adding the path changes the path's pixels and nothing else" \
  "$DIFF" "$T/with.png" "$T/without.png" --within "$T/mask.png" --grow 2 --min-changed 0.9
# ... and the check has teeth: a path drawn one waypoint short is caught.
python3 - "$T/syn.plans.jsonl" > "$T/short.jsonl" <<'PY'
import json, sys
p = [json.loads(l) for l in open(sys.argv[1])][-1]
p["waypoints"] = p["waypoints"][:-1]
print(json.dumps(p))
PY
python3 tests/render/png_tools.py path-mask "$T/short.jsonl" $W $H 30 20 0 0 "$T/short.png"
if ! "$DIFF" "$T/with.png" "$T/without.png" --within "$T/short.png" --grow 2 >/dev/null; then
  tap_ok "a mask missing the last path segment is reported"
else tap_not_ok "a mask missing the last path segment is reported"; fi

# Alternatives: each alternative alone (fake_traj keep: the plan with only
# that alternative) against none changes exactly its pixels, as png_tools.py
# draws them from its waypoints, and not those along the plan's path.
RIVER=(--log "$T/river_crossing.alt.in.log" --no-nodes --no-path "${opts[@]}")
"$B/bin/hylo-listen" --lcm-url "file://$T/river_crossing.alt.plan.log?speed=0" --json \
  > "$T/river.jsonl"
"$FAKE" keep "$T/river.none.log" - "$T/river_crossing.alt.plan.log"
"$RENDER" --quiet "${RIVER[@]}" --log "$T/river.none.log" --out "$T/noalt.png"
for i in 1 2; do
  "$FAKE" keep "$T/river.$i.log" $i "$T/river_crossing.alt.plan.log"
  "$RENDER" --quiet "${RIVER[@]}" --log "$T/river.$i.log" --out "$T/alt$i.png"
  grep "\"type\":\"alternative\",\"request_id\":1,\"index\":$i," "$T/river.jsonl" > "$T/alt$i.jsonl"
  python3 tests/render/png_tools.py alternatives-mask "$T/alt$i.jsonl" $W $H 40 40 0 0 "$T/altmask$i.png"
  tap_check "alternative $((i + 1)) changes its own pixels and nothing else" \
    "$DIFF" "$T/alt$i.png" "$T/noalt.png" --within "$T/altmask$i.png" --grow 2 --min-changed 0.9
done
head -1 "$T/river.jsonl" > "$T/river.plan.jsonl"
python3 tests/render/png_tools.py path-mask "$T/river.plan.jsonl" $W $H 40 40 0 0 "$T/planmask.png"
if ! "$DIFF" "$T/alt1.png" "$T/noalt.png" --within "$T/planmask.png" --grow 2 >/dev/null; then
  tap_ok "an alternative is not drawn along the plan's path"
else tap_not_ok "an alternative is not drawn along the plan's path"; fi
# All of them: the same pixels as the union of their masks.
render_top_alternatives "${opts[@]}" --no-path --out "$T/alt.png"
python3 tests/render/png_tools.py alternatives-mask "$T/river.jsonl" $W $H 40 40 0 0 "$T/altmask.png"
tap_check "all alternatives change their pixels and nothing else" \
  "$DIFF" "$T/alt.png" "$T/noalt.png" --within "$T/altmask.png" --grow 2 --min-changed 0.9
render_3d_alternatives --no-annotations --no-path --out "$T/alt3d.png"
render_3d_alternatives --no-annotations --no-path --no-alternatives --out "$T/noalt3d.png"
if ! "$DIFF" "$T/alt3d.png" "$T/noalt3d.png" --tolerance 0 --max-fraction 0 >/dev/null; then
  tap_ok "the 3-D view draws the alternatives"
else tap_not_ok "the 3-D view draws the alternatives"; fi
# --no-alternatives: the picture of the plan alone, byte for byte, in both
# views (fake_traj keep - republishes the plan without its alternatives).
for view in top 3d; do
  s=river_crossing; [ $view = 3d ] && s=chasm_030
  "$FAKE" keep "$T/$s.alone.log" - "$T/$s.alt.plan.log"
  "render_${view}_alternatives" --no-alternatives --out "$T/$view.noalt.png"
  "$RENDER" --quiet --log "$T/$s.alt.in.log" --log "$T/$s.alone.log" --no-nodes --camera "$CAMERA" \
    --view $view --out "$T/$view.alone.png"
  if cmp -s "$T/$view.noalt.png" "$T/$view.alone.png" &&
     ! cmp -s "$T/$view.noalt.png" "$T/${view}_alternatives.a.png"; then
    tap_ok "$view view: --no-alternatives draws the plan as if it had none"
  else tap_not_ok "$view view: --no-alternatives draws the plan as if it had none"; fi
done
# More alternatives than the renderer holds: an error naming the capacity
# (the bad-input checks below), and --no-alternatives still draws the plan.
"$FAKE" plan "$T/over.log" 9 "$T/river_crossing.alt.plan.log"
tap_check "--no-alternatives draws a plan whatever its alternatives" \
  "$RENDER" --quiet --log "$T/river_crossing.alt.in.log" --log "$T/over.log" --no-nodes \
  --no-alternatives --out "$T/over.png"

# An empty map (no obstacles, no water, no plan) renders the background and
# the ground colour only.
cat > "$T/empty.yaml" <<'EOF'
robot: ambot
map_id: 5
grid: {nx: 20, ny: 10, resolution_m: 1.0}
EOF
scene_log "$T/empty.yaml" --lcm-url "file://$T/empty.log?mode=w"
"$RENDER" --quiet --log "$T/empty.log" --map-only --no-annotations --width 200 --height 120 \
  --out "$T/empty.png"
cols=$(python3 tests/render/png_tools.py colours "$T/empty.png")
# 180 x 90 px of map (20 x 10 m at 9 px/m), the rest background
if [ "$(echo "$cols" | wc -l)" -eq 2 ] && echo "$cols" | grep -q " 16200$" &&
   echo "$cols" | grep -q "^247,247,247 "; then
  tap_ok "an empty map renders background and ground only"
else tap_not_ok "an empty map renders background and ground only" "$cols"; fi

# Bad input: a clear error, exit 1 or 2, and no PNG (an existing one untouched).
bad() {
  local name=$1 want=$2; shift 2
  rm -f "$T/bad.png"
  echo keep > "$T/old.png"
  "$RENDER" --quiet "$@" --out "$T/bad.png" > "$T/bad.out" 2>&1; local rc=$?
  "$RENDER" --quiet "$@" --out "$T/old.png" > /dev/null 2>&1
  if [ $rc -ne 0 ] && [ ! -e "$T/bad.png" ] && [ "$(cat "$T/old.png")" = keep ] &&
     grep -q "$want" "$T/bad.out" && [ -z "$(ls "$T" | grep '\.tmp\.')" ]; then
    tap_ok "bad input: $name"
  else tap_not_ok "bad input: $name" "exit $rc" "$(cat "$T/bad.out")"; fi
}
bad "missing log" "cannot open log $T/nothere.log" --log "$T/nothere.log"
printf 'not a log at all' > "$T/junk.log"
bad "a file that is not an LCM log" "junk.log holds no LCM events" --log "$T/junk.log"
bad "log without a map" "no map (channel HYLO_MAP)" --log "$T/di.plan.log"
bad "plan for another map" "is for map 1, which is not in the input" \
  --log "$T/syn.in.log" --log "$T/di.plan.log"
bad "no plan without --map-only" "no plan" --log "$T/di.in.log"
bad "unknown request id" "no plan with request_id 9" --log "$T/di.in.log" --log "$T/di.plan.log" \
  --request-id 9
bad "zero image size" "is not a size" --log "$T/di.in.log" --log "$T/di.plan.log" --width 0
bad "huge image size" "is not a size" --log "$T/di.in.log" --log "$T/di.plan.log" --height 100000
bad "bad camera" "is not AZ,EL" --log "$T/di.in.log" --log "$T/di.plan.log" --camera 1,95
bad "more alternatives than drawn" "plan 1 comes with 9 alternatives; hylo-render draws 1 to 8" \
  --log "$T/river_crossing.alt.in.log" --log "$T/over.log" --no-nodes
mkdir -p "$T/ro" && chmod 500 "$T/ro"
if [ "$(id -u)" -ne 0 ]; then
  "$RENDER" --quiet --log "$T/di.in.log" --log "$T/di.plan.log" --out "$T/ro/x.png" 2> "$T/ro.err"
  if [ $? -eq 1 ] && grep -q "cannot write" "$T/ro.err" && [ -z "$(ls "$T/ro")" ]; then
    tap_ok "unwritable output directory: error, nothing left behind"
  else tap_not_ok "unwritable output directory: error, nothing left behind" "$(cat "$T/ro.err")"; fi
else
  tap_skip "unwritable output directory" "running as root (permissions do not apply)"
fi
"$RENDER" --out "$T/x.png" > /dev/null 2>&1; rc=$?
if [ $rc -eq 2 ]; then tap_ok "no input: usage error (exit 2)"; else tap_not_ok "no input: usage error (exit 2)" "exit $rc"; fi
tap_check "--help lists --camera, --map-only and --no-alternatives" sh -c "'$RENDER' --help | grep -q -- --camera && '$RENDER' --help | grep -q -- --map-only && '$RENDER' --help | grep -q -- --no-alternatives"
tap_finish
