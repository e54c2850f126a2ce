#!/usr/bin/env python3
"""Figures of make casestudies from results.json (hylo-casestudies):
di_convergence.png, the graph cost of the double integrator against the
sample spacing with the swept two-phase optimum as the reference line (the
paper's Fig. 10).

usage: plot.py RESULTS.json OUT_DIR
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")   # offscreen, no display
import matplotlib.pyplot as plt  # noqa: E402


def convergence(di, out):
    conv = di["convergence"]
    pts = [p for p in conv["points"] if p["graph_cost"] is not None]
    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    ax.plot([p["spacing"] for p in pts], [p["graph_cost"] for p in pts], "o-", color="tab:red",
            label="graph path, exact edge costs")
    ax.axhline(conv["swept_optimum"], color="tab:green", ls="--",
               label=f"swept two-phase optimum {conv['swept_optimum']:.4f}")
    case = di["cases"][conv["case"] - 1]
    if case.get("naive_two_phase_cost") is not None:
        ax.axhline(case["naive_two_phase_cost"], color="tab:pink", ls=":",
                   label=f"two-phase from a naive guess {case['naive_two_phase_cost']:.4f}")
    ax.invert_xaxis()
    ax.set_xlabel("Poisson-disc spacing")
    ax.set_ylabel("cost  $\\int (u^2 + \\rho)\\,dt$")
    ax.set_title(f"double integrator {tuple(case['start'])} -> {tuple(case['goal'])}")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    # Fixed metadata: same results, same bytes.
    fig.savefig(os.path.join(out, "di_convergence.png"), metadata={"Software": None})
    plt.close(fig)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        res = json.load(f)
    os.makedirs(sys.argv[2], exist_ok=True)
    if "di" in res:
        convergence(res["di"], sys.argv[2])
        print(f"wrote {os.path.join(sys.argv[2], 'di_convergence.png')}")


if __name__ == "__main__":
    main()
