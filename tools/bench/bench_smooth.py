#!/usr/bin/env python3
"""Smoothing on generated scenes (tools/scene/gen_scenes.py), per robot.

    tools/bench/bench_smooth.py BUILD [--count N] [--robots ambot,drivocopter]
                                [--seed S] [--timeout SECONDS] [--jobs J] [--json PATH]

For each robot, N scenes (seeds S .. S + N - 1) are generated, planned by
hylo-planner and smoothed by hylo-smooth through file:// logs. Prints a table
and writes BUILD/bench/smooth_scenes.json, rows {name, value, unit,
reference, reference_value, ratio}: the fraction planned (status ok), the
fraction of planned scenes that got a trajectory, that the full optimization
smoothed, and that each fallback step smoothed (traj_t.method), and the
median smoothed / predicted energy. A smoothing that takes longer than
--timeout counts as no trajectory. Every published trajectory is also
walked from outside (tools/clearance_walk.py, with the .venv's Python: the
robot's body and the margin traj_t states): the fraction outside its domain
(target 0) and the fraction traj_t calls safe. Goals ask for the default
alternatives: the fraction of scenes whose published trajectory is not the
graph's first sequence, and what it saves against that one smoothed. The
per-scene lines go to
BUILD/bench/work/smooth/<robot>.jsonl.
"""
import argparse
import concurrent.futures
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
VENV_PY = os.path.join(ROOT, ".venv", "bin", "python")
METHODS = ["full", "straightened", "finer mesh", "via points", "phase by phase", "graph path"]


def run(cmd, timeout=None, env=None):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)


def can_walk():
    """The outside walk needs the .venv's lcm and PyYAML (make venv)."""
    return os.access(VENV_PY, os.X_OK) and run([VENV_PY, "-c", "import lcm, yaml"]).returncode == 0


def walk(build, robot, inp, traj):
    """tools/clearance_walk.py on a published trajectory: (inside, its summary line)."""
    w = run([VENV_PY, os.path.join(ROOT, "tools", "clearance_walk.py"), "--map-log", inp, "--traj-log", traj,
             "--robot-file", os.path.join(ROOT, "trainer", "params", robot + ".yaml")],
            env=dict(os.environ, HYLO_PY_BINDINGS=os.path.join(build, "gen", "lcm", "python")))
    return w.returncode == 0, (w.stdout + w.stderr).strip()[-300:]


def one(build, robot, scene, work, timeout, walking):
    """Plans and smooths one scene; a dict of what happened."""
    name = os.path.splitext(os.path.basename(scene))[0]
    d = os.path.join(work, name)
    os.makedirs(d, exist_ok=True)
    inp, plan, alll, traj = (os.path.join(d, f) for f in ("in.log", "plan.log", "all.log", "traj.log"))
    for f in (inp, plan, traj):
        if os.path.exists(f):
            os.remove(f)
    b = os.path.join(build, "bin")
    r = {"scene": name}
    run([f"{b}/hylo-scene", scene, "--goal", "--lcm-url", f"file://{inp}?mode=w"])
    run([f"{b}/hylo-planner", "--lcm-url", f"file://{inp}?speed=0", "--out-url", f"file://{plan}?mode=w"])
    p = run([f"{b}/hylo-listen", "--lcm-url", f"file://{plan}?speed=0", "--json"]).stdout.splitlines()
    if not p:
        r["plan"] = "none"
        return r
    pj = json.loads(p[0])
    r["plan"] = pj["status"]
    r["predicted_j"] = pj.get("total_cost_j")
    r["modes"] = pj.get("mode_sequence")
    if pj["status"] != "ok":
        return r
    with open(alll, "wb") as f:
        for x in (inp, plan):
            f.write(open(x, "rb").read())
    t0 = time.perf_counter()
    try:
        s = run([f"{b}/hylo-smooth", "--quiet", "--lcm-url", f"file://{alll}?speed=0",
                 "--out-url", f"file://{traj}?mode=w"], timeout=timeout)
        r["smooth_stderr"] = s.stderr[-2000:]
    except subprocess.TimeoutExpired:
        r["traj"] = "timeout"
        r["seconds"] = timeout
        return r
    r["seconds"] = time.perf_counter() - t0
    t = run([f"{b}/hylo-listen", "--lcm-url", f"file://{traj}?speed=0", "--json"]).stdout.splitlines()
    if not t:
        r["traj"] = "none"
        return r
    tj = json.loads(t[0])
    r["alternatives"] = [{k: a.get(k) for k in ("index", "mode_sequence", "predicted_j", "smoothed_j", "chosen")}
                         for a in map(json.loads, t[1:]) if a.get("type") == "traj_alternative"]
    r["traj"] = tj["status"]
    r["reason"] = tj["reason"]
    if tj["status"] == "ok":
        r["method"] = tj["method"]
        r["energy_j"] = tj["energy_j"]
        r["gap_j"] = tj["gap_j"]
        r["safe"] = tj["safe"]
        if walking:
            r["inside"], r["walk"] = walk(build, robot, inp, traj)
    return r


def row(name, value, unit, ref=None, ref_value=None):
    ratio = value / ref_value if ref_value not in (None, 0) and value is not None else None
    return {"name": name, "value": value, "unit": unit, "reference": ref, "reference_value": ref_value, "ratio": ratio}


def main(argv):
    ap = argparse.ArgumentParser(description="Smoothing on generated scenes (see the module docstring).")
    ap.add_argument("build")
    ap.add_argument("--count", type=int, default=50, help="scenes per robot (default 50)")
    ap.add_argument("--robots", default="ambot,drivocopter")
    ap.add_argument("--seed", type=int, default=1, help="first seed (default 1)")
    ap.add_argument("--timeout", type=float, default=900, help="seconds per smoothing (default 900)")
    ap.add_argument("--jobs", type=int, default=1, help="scenes at a time (default 1)")
    ap.add_argument("--json", help="where the rows go (default BUILD/bench/smooth_scenes.json)")
    a = ap.parse_args(argv)
    work = os.path.join(a.build, "bench", "work", "smooth")
    os.makedirs(work, exist_ok=True)
    here = os.path.dirname(os.path.abspath(__file__))
    rows = []
    walking = can_walk()
    if not walking:
        print("no .venv with lcm and PyYAML (make venv): trajectories are not walked from outside")
    for robot in a.robots.split(","):
        scenes_dir = os.path.join(work, "scenes", robot)
        out = run([sys.executable, os.path.join(here, "..", "scene", "gen_scenes.py"), "--robot", robot,
                   "--seed", str(a.seed), "--count", str(a.count), "--out", scenes_dir])
        if out.returncode:
            raise SystemExit(out.stderr)
        scenes = out.stdout.split()
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as ex:
            results = list(ex.map(lambda s: one(a.build, robot, s, work, a.timeout, walking), scenes))
        with open(os.path.join(work, f"{robot}.jsonl"), "w") as f:
            for r in results:
                f.write(json.dumps(r) + "\n")
        n = len(results)
        planned = [r for r in results if r["plan"] == "ok"]
        got = [r for r in planned if r.get("traj") == "ok"]
        np_ = max(1, len(planned))
        ratios = [r["energy_j"] / r["predicted_j"] for r in got if r.get("predicted_j")]
        print(f"{robot}: {n} generated scenes (seeds {a.seed}..{a.seed + n - 1})")
        print(f"  planned                        {len(planned):4d} / {n}")
        print(f"  got a trajectory               {len(got):4d} / {len(planned)}")
        rows.append(row(f"smooth_{robot}_planned_fraction", len(planned) / n, "fraction"))
        rows.append(row(f"smooth_{robot}_trajectory_fraction", len(got) / np_, "fraction", "target", 1.0))
        for m in METHODS:
            k = sum(1 for r in got if r.get("method") == m)
            print(f"  from {m:25s} {k:4d} / {len(planned)}")
            key = m.replace(" ", "_")
            rows.append(row(f"smooth_{robot}_{key}_fraction", k / np_, "fraction",
                            "target" if m == "full" else None, 0.95 if m == "full" else None))
        safe = sum(1 for r in got if r.get("safe"))
        print(f"  traj_t safe (body + margin)    {safe:4d} / {len(got)}")
        rows.append(row(f"smooth_{robot}_safe_fraction", safe / max(1, len(got)), "fraction", "target", 1.0))
        if walking:
            outside = [r for r in got if not r.get("inside")]
            print(f"  outside by the outside walk    {len(outside):4d} / {len(got)}")
            rows.append(row(f"smooth_{robot}_outside_fraction", len(outside) / max(1, len(got)), "fraction",
                            "target", 0.0))
            for r in outside:
                print(f"  outside: {r['scene']}: {r.get('walk', '')}")
        # The graph's first sequence against the one published (alternatives).
        other = [r for r in got if any(a["chosen"] and a["index"] > 0 for a in r.get("alternatives", []))]
        savings = []
        for r in other:
            first = next((a for a in r["alternatives"] if a["index"] == 0), None)
            if first and first.get("smoothed_j"):
                savings.append(1 - r["energy_j"] / first["smoothed_j"])
        print(f"  another sequence than the first  {len(other):4d} / {len(got)}" +
              (f" (saving {statistics.median(savings):.1%} median, {max(savings):.1%} most)" if savings else ""))
        rows.append(row(f"smooth_{robot}_other_sequence_fraction", len(other) / max(1, len(got)), "fraction"))
        if savings:
            rows.append(row(f"smooth_{robot}_other_sequence_saving_median", statistics.median(savings), "fraction"))
        if ratios:
            med = statistics.median(ratios)
            print(f"  smoothed / predicted energy    median {med:.3f}, range {min(ratios):.3f} .. {max(ratios):.3f}")
            rows.append(row(f"smooth_{robot}_smoothed_over_predicted_median", med, "ratio"))
        secs = [r["seconds"] for r in planned if "seconds" in r]
        if secs:
            rows.append(row(f"smooth_{robot}_seconds_median", statistics.median(secs), "s"))
            print(f"  seconds per smoothing          median {statistics.median(secs):.1f}, max {max(secs):.1f}")
        for r in planned:
            if r.get("traj") != "ok":
                print(f"  no trajectory: {r['scene']}: {r.get('traj')}: {r.get('reason', '')[:300]}")
    path = a.json or os.path.join(a.build, "bench", "smooth_scenes.json")
    json.dump(rows, open(path, "w"), indent=1)
    print(f"{len(rows)} figures -> {path}")


if __name__ == "__main__":
    main(sys.argv[1:])
