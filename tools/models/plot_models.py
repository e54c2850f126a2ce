#!/usr/bin/env python3
"""Pictures of a committed cost model, like the paper's Figs. 3 and 6:
  <robot>_<mode>_training.png  training trajectories (re-solved from the
                               dataset's rows with `trainer --solve
                               --trajectory`), coloured by their energy
  <robot>_<mode>_contour.png   the learned cost (hylo-cost: the onboard
                               evaluator and the committed header) from
                               (0, 0, vx, theta) to every (x, y, vx, theta),
                               vx = 1.0 m/s (marine: 0.5), theta = pi/2;
                               flight: hover at the origin to hover at every
                               (x, 0, z), the paper's xz slice; edges the
                               feasibility classifier rejects blank

usage: plot_models.py ROBOT MODE OUT_DIR [--trajectories N]
Run from the repository root after `make` (uses build/bin/trainer and
build/bin/hylo-cost). Same dataset and models, same pictures.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")   # offscreen
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import cm, colors  # noqa: E402

BIN = os.environ.get("BUILD", "build") + "/bin"


def fitted_samples(robot, mode):
    """The committed model's sample count: its fit used the dataset's first
    that many rows (the dataset may have grown since)."""
    header = f"onboard/models/{robot}_{mode}.h"
    with open(header) as f:
        for line in f:
            if line.startswith(" * samples: "):
                return int(line.split()[2])
    sys.exit(f"{header}: no ' * samples: ' line")


def training_rows(robot, mode, n):
    """n converged rows spread evenly over the rows the committed model was
    fitted on (deterministic)."""
    path = f"trainer/datasets/{robot}/{mode}.csv"
    samples = fitted_samples(robot, mode)
    with open(path) as f:
        rows = [r for k, r in zip(range(samples), csv.DictReader(f)) if r["converged"] == "1"]
    if not rows:
        sys.exit(f"{path}: no converged rows")
    step = max(1, len(rows) // n)
    return rows[::step][:n]


def solve(robot, mode, row):
    d = sum(1 for k in row if k.startswith("x1_"))
    x1 = ",".join(row[f"x1_{k}"] for k in range(d))
    x2 = ",".join(row[f"x2_{k}"] for k in range(d))
    out = subprocess.run([f"{BIN}/trainer", "--mode", mode, "--robot", robot, "--solve", x1, x2,
                          "--json", "--trajectory"], capture_output=True, text=True)
    if out.returncode != 0:
        return None
    j = json.loads(out.stdout)
    return j if j.get("converged") else None


def training_picture(robot, mode, n, out):
    sols = [s for s in (solve(robot, mode, r) for r in training_rows(robot, mode, n)) if s]
    if not sols:
        sys.exit(f"{robot} {mode}: no training trajectory re-solved")
    flight = mode == "flight"
    up = 2 if flight else 1   # flight: the xz projection, like the paper's Fig. 6
    costs = [s["cost_j"] for s in sols]
    norm = colors.Normalize(min(costs), max(costs))
    fig, ax = plt.subplots(figsize=(6, 5.5), dpi=120)
    for s in sorted(sols, key=lambda s: -s["cost_j"]):
        xs = [p[0] for p in s["trajectory"]["x"]]
        ys = [p[up] for p in s["trajectory"]["x"]]
        c = cm.viridis(norm(s["cost_j"]))
        ax.plot(xs, ys, color=c, lw=1.2)
        ax.plot(xs[-1], ys[-1], "o", color=c, ms=3)
    ax.plot(0, 0, "k^", ms=7, label="start (0, 0)")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]" if flight else "y [m]")
    ax.set_title(f"{robot} {mode}: {len(sols)} training trajectories" + (" (xz)" if flight else ""))
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left")
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cm.viridis), ax=ax, label="energy [J]")
    fig.tight_layout()
    path = os.path.join(out, f"{robot}_{mode}_training.png")
    fig.savefig(path, metadata={"Software": None})
    plt.close(fig)
    print(f"wrote {path}")


def predicted(robot, mode, a, b):
    out = subprocess.run([f"{BIN}/hylo-cost", "--robot", robot, "--mode", mode, "--json",
                          ",".join(map(str, a)), ",".join(map(str, b))], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"hylo-cost: {out.stderr.strip()}")
    return json.loads(out.stdout)


def ends(mode, x, y):
    """The contour's start and end sampled states for grid point (x, y)."""
    if mode == "flight":
        return (0, 0, 0, 0, 0, 0), (x, 0, y, 0, 0, 0)
    v = 1.0 if mode == "ground" else 0.5
    return (0, 0, v, math.pi / 2), (x, y, v, math.pi / 2)


def contour_picture(robot, mode, out, n=41):
    flight = mode == "flight"
    reach = 9.0 if flight else 4.5
    grid = [-reach + 2 * reach * i / (n - 1) for i in range(n)]
    z = []
    for y in grid:
        row = []
        for x in grid:
            if math.hypot(x, y) > reach or (x == 0 and y == 0):
                row.append(float("nan"))
                continue
            j = predicted(robot, mode, *ends(mode, x, y))
            feasible = (j.get("feasibility") or {}).get("feasible", True)
            row.append(j["planner_cost_j"] if feasible else float("nan"))
        z.append(row)
    fig, ax = plt.subplots(figsize=(6, 5.5), dpi=120)
    cs = ax.contourf(grid, grid, z, levels=20, cmap="viridis")
    ax.contour(grid, grid, z, levels=10, colors="k", linewidths=0.4)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    if flight:
        ax.plot(0, 0, "r^", ms=7)
        ax.set_ylabel("z [m]")
        ax.set_title(f"{robot} {mode}: learned energy, hover at (0, 0, 0)\nto hover at (x, 0, z)", fontsize=10)
    else:
        v = ends(mode, 0, 0)[0][2]
        ax.annotate("", xy=(0, 0.8), xytext=(0, 0), arrowprops={"arrowstyle": "->", "color": "red", "lw": 2})
        ax.set_ylabel("y [m]")
        ax.set_title(f"{robot} {mode}: learned energy from (0, 0)\nv = {v} m/s, heading pi/2 at both ends",
                     fontsize=10)
    fig.colorbar(cs, ax=ax, label="predicted energy [J]")
    fig.tight_layout()
    path = os.path.join(out, f"{robot}_{mode}_contour.png")
    fig.savefig(path, metadata={"Software": None})
    plt.close(fig)
    print(f"wrote {path}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("robot")
    p.add_argument("mode")
    p.add_argument("out")
    p.add_argument("--trajectories", type=int, default=40)
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    contour_picture(a.robot, a.mode, a.out)
    training_picture(a.robot, a.mode, a.trajectories, a.out)


if __name__ == "__main__":
    main()
