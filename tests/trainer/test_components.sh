#!/usr/bin/env bash
# The trainer's files depend on each other without cycles: a component is
# X.hpp with X.cpp, and X depends on Y when one of X's files has
# #include "trainer/Y.hpp". A cycle (say clearance -> smoother -> corridor ->
# clearance, as the smoother once had) means no file of it can be read or
# changed alone. The check itself must find a cycle: it is run on a made-up
# one first.
set -u
cd "$(dirname "$0")/../.."
. tests/tap.sh
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

# cycles DIR: one line per component cycle among DIR's .hpp/.cpp files, none if none.
cycles() {
  python3 - "$1" <<'PY'
import os, re, sys
d = sys.argv[1]
deps = {}
for f in sorted(os.listdir(d)):
    if f.endswith((".hpp", ".cpp")):
        c = f.rsplit(".", 1)[0]
        text = open(os.path.join(d, f)).read()
        deps.setdefault(c, set()).update(
            y for y in re.findall(r'^\s*#\s*include\s+"trainer/([^"/]+)\.hpp"', text, re.M) if y != c)
# Tarjan's strongly connected components, without recursion.
index, low, on, stack, out, n = {}, {}, set(), [], [], 0
for root in sorted(deps):
    if root in index:
        continue
    work = [(root, iter(sorted(deps[root])))]
    index[root] = low[root] = n; n += 1; stack.append(root); on.add(root)
    while work:
        v, it = work[-1]
        w = next(it, None)
        if w is not None:
            if w not in deps:
                continue
            if w not in index:
                index[w] = low[w] = n; n += 1; stack.append(w); on.add(w)
                work.append((w, iter(sorted(deps[w]))))
            elif w in on:
                low[v] = min(low[v], index[w])
            continue
        work.pop()
        if work:
            low[work[-1][0]] = min(low[work[-1][0]], low[v])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); on.discard(w); comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(" ".join(sorted(comp)))
print("\n".join(out))
PY
}

mkdir -p "$T/made_up"
printf '#include "trainer/b.hpp"\n' > "$T/made_up/a.hpp"
printf '#include "trainer/a.hpp"\n' > "$T/made_up/b.cpp"
printf '#include "trainer/a.hpp"\n' > "$T/made_up/c.cpp"
found=$(cycles "$T/made_up")
if [ "$found" = "a b" ]; then tap_ok "the check finds a made-up cycle a -> b -> a (c outside it)"
else tap_not_ok "the check finds a made-up cycle a -> b -> a (c outside it)" "found: '$found'"; fi

found=$(cycles trainer)
if [ -z "$found" ]; then tap_ok "no component cycle among trainer/'s files"
else tap_not_ok "no component cycle among trainer/'s files" "$found"; fi
tap_finish
