#!/usr/bin/env bash
# make install and make uninstall, and the installed hylo used the way its
# users use it (docs/install.md). Staged with DESTDIR: a C99 program built
# out of the tree with pkg-config (hylo) and a C++17 one with CMake
# (find_package(hylo), hylo::onboard) plan the double integrator's scene
# with the installed models, and their plans equal the in-tree build's bit
# for bit (tools/cross/plan_digest); a C program with pkg-config hylo-lcm
# publishes a plan over LCM. Every installed header compiles on its own
# (C99 and C++17); the installed headers are the API and the workspace's
# layout, nothing private to the core; one version everywhere; the
# installed tools run and the installed trainer finds its installed robot
# files; a second install without DESTDIR into other folders (LIBDIR
# lib/<multiarch>) works from there. Uninstall removes exactly what install
# put. A -DHYLO_... capacity of the build reaches hylo.pc and hylo::onboard.
# Prints TAP.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
B=${BUILD:-build}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
CC=${CC:-gcc}
CXX=${CXX:-g++}
# The make running this test may hand down a jobserver this make cannot use.
MAKEFLAGS=$(echo "${MAKEFLAGS:-}" | sed -E 's/--jobserver-(auth|fds)=[^ ]*//g')
export MAKEFLAGS
unset MAKELEVEL
version=$(sed -n 's/^#define HYLO_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)$/\2/p' onboard/include/hylo/version.h |
  paste -sd.)
want_plan=$("$B/cross/plan_digest" 2>&1 | grep '^model_di ')

# The stage holds files of other packages, which must survive.
S=$T/stage
P=/usr/local
mkdir -p "$S$P/include" "$S$P/lib/pkgconfig" "$S$P/bin" "$S$P/share/doc"
echo '/* another package */' > "$S$P/include/other.h"
echo 'Name: other' > "$S$P/lib/pkgconfig/other.pc"
echo other > "$S$P/share/doc/other"
list() { (cd "$1" && find . \( -type f -o -type l \) | sort); }
list "$S" > "$T/before"

if make --no-print-directory install DESTDIR="$S" PREFIX=$P > "$T/install.log" 2>&1; then
  tap_ok "make install DESTDIR=... PREFIX=$P"; else
  tap_not_ok "make install DESTDIR=... PREFIX=$P" "$(tail -5 "$T/install.log")"; fi
I=$S$P/include

# The headers: hylo/*.h and hylo/internal/*.h exactly, nothing of src/.
want=$( (cd onboard/include && ls hylo/*.h hylo/internal/*.h) | sort)
have=$( (cd "$I" && ls hylo/*.h hylo/internal/*.h) 2>/dev/null | sort)
if [ -n "$have" ] && [ "$want" = "$have" ] && [ -z "$(find "$S" -name 'planner_internal.h')" ]; then
  tap_ok "the installed headers are the API and the workspace's layout (hylo/internal), none of the core's own"; else
  tap_not_ok "the installed headers are the API and the workspace's layout (hylo/internal), none of the core's own" \
    "$(diff <(echo "$want") <(echo "$have") | head -5)"; fi
bad=""
for h in $have; do
  printf '#include <%s>\nint hylo_header_check;\n' "$h" > "$T/h.c"
  "$CC" -std=c99 -Wall -Wextra -Werror -pedantic -I"$I" -c "$T/h.c" -o "$T/h.o" 2> "$T/h.err" || bad="$bad C:$h"
  "$CXX" -std=c++17 -Wall -Wextra -Werror -pedantic -x c++ -I"$I" -c "$T/h.c" -o "$T/h.o" 2>> "$T/h.err" ||
    bad="$bad C++:$h"
done
# The models: C99 data with designated initializers, which C++17 accepts as
# GNU's extension (no -pedantic), every field given (-Wextra).
for h in $( (cd "$I" && ls hylo/models/*.h) 2>/dev/null); do
  printf '#include <%s>\nint hylo_header_check;\n' "$h" > "$T/h.c"
  "$CC" -std=c99 -Wall -Wextra -Werror -pedantic -I"$I" -c "$T/h.c" -o "$T/h.o" 2> "$T/h.err" || bad="$bad C:$h"
  "$CXX" -std=c++17 -Wall -Wextra -Werror -x c++ -I"$I" -c "$T/h.c" -o "$T/h.o" 2>> "$T/h.err" || bad="$bad C++:$h"
done
if [ -z "$bad" ]; then
  tap_ok "each installed header, models included, compiles on its own as C99 and as C++17 (extern \"C\" inside)"; else
  tap_not_ok "each installed header, models included, compiles on its own as C99 and as C++17" "fails:$bad" \
    "$(head -5 "$T/h.err")"; fi
n_models=$(ls onboard/models/*.h | wc -l)
if [ "$(ls "$I"/hylo/models/*.h 2>/dev/null | wc -l)" -eq "$n_models" ] &&
   [ -f "$S$P/lib/libhylo.a" ] && [ -f "$S$P/lib/libhylo_lcm.a" ] && [ -f "$I/hylo/lcm/hylo_plan_t.h" ] &&
   [ -f "$I/hylo/lcm/hylo_msg.h" ] && [ -f "$I/hylo/plan_t.hpp" ] && [ -f "$S$P/share/hylo/msgs/plan_t.lcm" ] &&
   [ -f "$S$P/share/hylo/python/hylo/__init__.py" ] && [ -f "$S$P/share/hylo/params/ambot.yaml" ]; then
  tap_ok "installed: libhylo.a, libhylo_lcm.a, the $n_models models, the .lcm files and their C, C++ and Python bindings, the robot files"; else
  tap_not_ok "installed: the libraries, the models, the messages and their bindings, the robot files" \
    "$(list "$S" | grep -v -F -x -f "$T/before" | head -20)"; fi

# One version: version.h, hylo.pc, the trainer.
export PKG_CONFIG_PATH=$S$P/lib/pkgconfig PKG_CONFIG_SYSROOT_DIR=$S
export PKG_CONFIG_LIBDIR=$PKG_CONFIG_PATH   # the stage's .pc files only
trainer_version=$("$S$P/bin/hylo-trainer" --version 2>/dev/null | head -1)
if [ -n "$version" ] && [ "$(pkg-config --modversion hylo 2>&1)" = "$version" ] &&
   [ "$(pkg-config --modversion hylo-lcm 2>&1)" = "$version" ] && [ "$trainer_version" = "hylo trainer $version" ]; then
  tap_ok "one version, $version: hylo/version.h, hylo.pc, hylo-lcm.pc, hylo-trainer --version"; else
  tap_not_ok "one version: hylo/version.h, hylo.pc, hylo-lcm.pc, hylo-trainer --version" \
    "version.h '$version', hylo.pc '$(pkg-config --modversion hylo 2>&1)', trainer '$trainer_version'"; fi

# Out of the tree, as users build: only the installed files.
mkdir -p "$T/src"
cp tests/install/consumer.h tests/install/consumer.c tests/install/consumer_lcm.c "$T/src/"
cp -r tests/install/cmake "$T/src/cmake"
flags=$(pkg-config --cflags --libs hylo 2>&1)
if [[ $flags == *"-I$I"* && $flags == *"-L$S$P/lib"* && $flags == *"-lhylo"* ]]; then
  tap_ok "pkg-config --cflags --libs hylo points into the stage (PKG_CONFIG_SYSROOT_DIR)"; else
  tap_not_ok "pkg-config --cflags --libs hylo points into the stage (PKG_CONFIG_SYSROOT_DIR)" "$flags"; fi
(cd "$T/src" && "$CC" -std=c99 -Wall -Wextra -Werror -pedantic consumer.c $(pkg-config --cflags --libs hylo) \
  -o consumer) > "$T/cc.log" 2>&1 && "$T/src/consumer" > "$T/c.out" 2> "$T/c.err"; rc=$?
if [ "$rc" -eq 0 ] && [ -n "$want_plan" ] && [ "$(head -1 "$T/c.out")" = "$want_plan" ]; then
  tap_ok "a C99 program built with pkg-config hylo plans the scene with the installed models, bit for bit the in-tree plan"; else
  tap_not_ok "a C99 program built with pkg-config hylo plans the scene with the installed models, bit for bit the in-tree plan" \
    "exit $rc" "got:  $(head -1 "$T/c.out")" "want: $want_plan" "$(cat "$T/cc.log" "$T/c.err" | head -5)"; fi
sed 's/^/# /' "$T/c.out"
(cd "$T/src" && "$CC" -std=c99 -Wall -Wextra -Werror -pedantic consumer_lcm.c \
  $(pkg-config --cflags --libs hylo-lcm) -o consumer_lcm) > "$T/lcm.log" 2>&1 && "$T/src/consumer_lcm" >> "$T/lcm.log" 2>&1
if [ $? -eq 0 ] && grep -q 'plan_t over memq://: 2 waypoints' "$T/lcm.log"; then
  tap_ok "a C99 program built with pkg-config hylo-lcm publishes a plan over LCM (memq://) and receives it"; else
  tap_not_ok "a C99 program built with pkg-config hylo-lcm publishes a plan over LCM (memq://) and receives it" \
    "$(tail -5 "$T/lcm.log")"; fi

# CMake, from the stage: the package finds its files relative to itself.
cmake_consumer() {   # BUILD-DIR PREFIX
  cmake -S "$T/src/cmake" -B "$1" -DCMAKE_PREFIX_PATH="$2" -DCMAKE_CXX_COMPILER="$CXX" > "$1.log" 2>&1 &&
    cmake --build "$1" >> "$1.log" 2>&1 && "$1/consumer" > "$1.out" 2>> "$1.log"
}
cmake_consumer "$T/cmake" "$S$P"; rc=$?
if [ "$rc" -eq 0 ] && [ "$(head -1 "$T/cmake.out")" = "$want_plan" ] &&
   grep -q 'plan_t round-trips through the C++ binding' "$T/cmake.out"; then
  tap_ok "a C++17 program built with find_package(hylo) and hylo::onboard, hylo::lcm plans bit for bit the same, and uses the C++ LCM binding"; else
  tap_not_ok "a C++17 program built with find_package(hylo) and hylo::onboard, hylo::lcm plans bit for bit the same" \
    "exit $rc" "got:  $(head -1 "$T/cmake.out" 2>/dev/null)" "want: $want_plan" "$(tail -8 "$T/cmake.log")"; fi
mkdir -p "$T/v"
printf 'cmake_minimum_required(VERSION 3.13)\nproject(v NONE)\nfind_package(hylo ${WANT} REQUIRED)\n' > "$T/v/CMakeLists.txt"
major=${version%%.*}; minor=${version#*.}; minor=${minor%%.*}
find_version() { rm -rf "$T/v/b"; cmake -S "$T/v" -B "$T/v/b" -DCMAKE_PREFIX_PATH="$S$P" "-DWANT=$1" > "$T/v.log" 2>&1; }
found=""; refused=""
for want in "$version" "$major.$minor" "$version;EXACT"; do find_version "$want" && found="$found, $want"; done
for want in "$major.$((minor + 1))" "$((major + 1)).0" "$version.1"; do find_version "$want" || refused="$refused, $want"; done
if [ "$found" = ", $version, $major.$minor, $version;EXACT" ] &&
   [ "$refused" = ", $major.$((minor + 1)), $((major + 1)).0, $version.1" ]; then
  tap_ok "find_package(hylo V): found for $version, $major.$minor, $version EXACT; refused for $major.$((minor + 1)), $((major + 1)).0, $version.1"; else
  tap_not_ok "find_package(hylo V): the right versions found and refused" "found${found:-: none}" "refused${refused:-: none}"; fi

# The tools and the trainer, run from the stage and from elsewhere.
missing=""
for t in hylo-planner hylo-scene hylo-listen hylo-render hylo-pngdiff hylo-cost hylo-envelope-tightness hylo-smooth hylo-trainer; do
  [ -x "$S$P/bin/$t" ] || missing="$missing $t"
done
if [ -z "$missing" ] && "$S$P/bin/hylo-planner" --help > /dev/null 2>&1 &&
   (cd "$T" && env -u HYLO_PARAMS_DIR "$S$P/bin/hylo-trainer" --mode di_neg --robot di --solve -0.5,0 -0.3,0 --json) \
     > "$T/solve.json" 2> "$T/solve.err" && grep -q '"status":"solved"' "$T/solve.json"; then
  tap_ok "the tools are installed; hylo-trainer, run outside any checkout, solves with the installed robot files"; else
  tap_not_ok "the tools are installed; hylo-trainer, run outside any checkout, solves with the installed robot files" \
    "missing:${missing:- none}" "$(head -3 "$T/solve.err" 2>/dev/null)"; fi
if PYTHONPATH=$S$P/share/hylo/python python3 -c "
from hylo import plan_t
m = plan_t(); m.robot = 'di'; m.reason = 'ok'; m.total_cost_j = 2.5
d = plan_t.decode(m.encode()); assert d.robot == 'di' and d.total_cost_j == 2.5" > "$T/py.log" 2>&1; then
  tap_ok "the installed Python bindings encode and decode a plan_t"; else
  tap_not_ok "the installed Python bindings encode and decode a plan_t" "$(tail -3 "$T/py.log")"; fi

# Uninstall: exactly what install put; a file the user added to a hylo
# folder, and that folder, stay.
echo mine > "$S$P/share/hylo/params/mine.yaml"
if make --no-print-directory uninstall DESTDIR="$S" PREFIX=$P > "$T/uninstall.log" 2>&1 &&
   [ "$(list "$S")" = "$( (cat "$T/before"; echo ./usr/local/share/hylo/params/mine.yaml) | sort)" ] &&
   [ ! -e "$I/hylo" ] && [ ! -e "$S$P/lib/cmake/hylo" ] && [ -d "$S$P/share/hylo/params" ] &&
   [ ! -e "$S$P/share/hylo/msgs" ]; then
  tap_ok "make uninstall removes every file install put and hylo's emptied folders, and nothing else"; else
  tap_not_ok "make uninstall removes every file install put and hylo's emptied folders, and nothing else" \
    "$(diff "$T/before" <(list "$S") | head -10)" "$(tail -3 "$T/uninstall.log")"; fi

# Another layout, no DESTDIR: LIBDIR lib/<multiarch>, used from its prefix.
unset PKG_CONFIG_SYSROOT_DIR
O=$T/opt/hylo
arch=$("$CC" -print-multiarch 2>/dev/null || echo x86_64-linux-gnu)
export PKG_CONFIG_PATH=$O/lib/$arch/pkgconfig PKG_CONFIG_LIBDIR=$O/lib/$arch/pkgconfig
if make --no-print-directory install PREFIX="$O" LIBDIR="$O/lib/$arch" > "$T/install2.log" 2>&1 &&
   [ "$(pkg-config --variable=libdir hylo)" = "$O/lib/$arch" ] &&
   (cd "$T/src" && "$CC" -std=c99 consumer.c $(pkg-config --cflags --libs hylo) -o consumer2) > "$T/cc2.log" 2>&1 &&
   [ "$("$T/src/consumer2" | head -1)" = "$want_plan" ] &&
   cmake_consumer "$T/cmake2" "$O" && [ "$(head -1 "$T/cmake2.out")" = "$want_plan" ]; then
  tap_ok "installed to PREFIX=$O with LIBDIR lib/$arch: pkg-config and CMake consumers plan bit for bit the same"; else
  tap_not_ok "installed to another PREFIX with LIBDIR lib/$arch: pkg-config and CMake consumers plan bit for bit the same" \
    "$(tail -3 "$T/install2.log" "$T/cc2.log" "$T/cmake2.log" 2>/dev/null)"; fi
if make --no-print-directory uninstall PREFIX="$O" LIBDIR="$O/lib/$arch" > "$T/uninstall2.log" 2>&1 &&
   [ -z "$(find "$O" \( -type f -o -type l \))" ]; then
  tap_ok "make uninstall with the same folders leaves no file behind"; else
  tap_not_ok "make uninstall with the same folders leaves no file behind" "$(find "$O" -type f | head -5)"; fi
# Capacities the library is built with reach the consumers' compilations.
if make --no-print-directory install-gen BUILD="$T/gen" CPPFLAGS='-DHYLO_MAX_NODES=20000 -Wdate-time' \
     > "$T/gen.log" 2>&1 &&
   grep -q '^Cflags: -I${includedir} -DHYLO_MAX_NODES=20000$' "$T/gen/install/hylo.pc" &&
   grep -q 'INTERFACE_COMPILE_DEFINITIONS "HYLO_MAX_NODES=20000"' "$T/gen/install/hyloConfig.cmake"; then
  tap_ok "a -DHYLO_... of the build's CPPFLAGS goes into hylo.pc's Cflags and hylo::onboard's definitions"; else
  tap_not_ok "a -DHYLO_... of the build's CPPFLAGS goes into hylo.pc's Cflags and hylo::onboard's definitions" \
    "$(grep Cflags "$T/gen/install/hylo.pc" 2>/dev/null)" "$(tail -3 "$T/gen.log")"; fi
tap_finish
