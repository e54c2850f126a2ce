#!/usr/bin/env python3
"""The cost models' error on the planner's own edges (issue #43), from the
per-edge CSV of tools/bench/bench_accuracy.cpp:
  left   relative error (prediction - exact) / exact against edge length,
         one colour per model, circles the edges the search evaluated,
         crosses the edges of its plans (symmetric log scale)
  right  the flight model's relative error against the climb angle of the
         edge's displacement (the roadmap's velocities are level)
with the held-out p95 of each model's provenance as a reference band.

usage: plot_accuracy.py EDGES.csv OUT.png
Run from the repository root (reads the held-out errors from
onboard/models/*.h) with the git-ignored venv (`make venv-report`).
"""
import csv
import math
import re
import sys

import matplotlib

matplotlib.use("Agg")   # offscreen
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"ambot_ground": "tab:brown", "ambot_marine": "tab:blue", "drivocopter_ground": "tab:olive",
           "drivocopter_flight": "tab:red", "di_di_neg": "tab:purple", "di_di_pos": "tab:pink"}


def held_out_p95(model):
    """The held-out p95 relative error in a committed header's provenance."""
    with open(f"onboard/models/{model}.h") as f:
        m = re.search(r"held-out errors: median [0-9.]+, p95 ([0-9.]+)", f.read())
    return float(m.group(1)) if m else math.nan


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["rel_error"] not in ("", "nan")]
    if not rows:
        sys.exit(f"{sys.argv[1]}: no solved edges")
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5.2), gridspec_kw={"width_ratios": [3, 2]})
    for model in sorted({r["model"] for r in rows}):
        for source, marker in (("evaluated", "o"), ("plan", "x")):
            pts = [r for r in rows if r["model"] == model and r["source"] == source]
            if not pts:
                continue
            ax.scatter([float(r["length_m"]) for r in pts], [100 * float(r["rel_error"]) for r in pts],
                       s=14, marker=marker, color=COLOURS.get(model, "k"), alpha=0.75,
                       label=f"{model} ({'search' if source == 'evaluated' else 'plans'}, {len(pts)})")
    ax.axhline(0, color="k", lw=0.6)
    ax.set_yscale("symlog", linthresh=2)   # linear within +-2%: the double integrator's errors reach 250%
    ax.set_xlabel("edge length [m] (flight: 3-D; double integrator: phase plane)")
    ax.set_ylabel("relative error of the model [%] (linear within +-2%)")
    ax.set_title("model error on the planner's edges, every committed scene")
    ax.legend(fontsize=7, ncol=2, loc="best")
    ax.grid(alpha=0.3)
    flight = [r for r in rows if r["model"] == "drivocopter_flight"]
    p95 = 100 * held_out_p95("drivocopter_flight")
    bx.axhspan(-p95, p95, color="tab:red", alpha=0.08, label=f"held-out p95 ({p95:.1f}%)")
    for source, marker in (("evaluated", "o"), ("plan", "x")):
        pts = [r for r in flight if r["source"] == source]
        bx.scatter([float(r["climb_deg"]) for r in pts], [100 * float(r["rel_error"]) for r in pts], s=16,
                   marker=marker, color="tab:red", alpha=0.75,
                   label=f"{'search' if source == 'evaluated' else 'plans'} ({len(pts)})")
    bx.axhline(0, color="k", lw=0.6)
    bx.set_xlabel("climb angle of the displacement [deg]")
    bx.set_ylabel("relative error [%]")
    bx.set_title("drivocopter_flight")
    bx.legend(fontsize=8)
    bx.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    print(f"{len(rows)} edges -> {sys.argv[2]}")


if __name__ == "__main__":
    main()
