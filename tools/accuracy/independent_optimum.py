#!/usr/bin/env python3
"""Labels against an independent optimum (issue #35's check, made at home):
planar boundary-value problems drawn here, solved by a different
transcription with many random starts, replayed, and by `trainer --solve`.

The independent solve: Legendre-Gauss-Radau collocation (degree 3,
--intervals intervals, the control linear between the interval ends) of
docs/models.md's dynamics (tools/bench/casadi_hs.py writes them once) in
CasADi + Ipopt, free duration, from --starts random paths (straight lines,
forward and reverse cubics between the ends, random mixes); the cheapest
converged one is replayed with CVODE under its own control. The trainer
solves each problem with its training options at each of --segments.

usage: independent_optimum.py ROBOT MODE OUT.jsonl [--problems N] [--seed S]
           [--starts K] [--intervals N] [--segments 20,40] [--reuse OLD.jsonl]
Run from a built clone with the venv that `make bench` makes (CasADi).
Each problem is a line of OUT.jsonl (appended; a re-run skips the problems
already there); a summary closes the run. --reuse takes the independent
optima of an earlier run's problems (the same draw), so a changed trainer
is checked again without solving them again.
"""
import argparse
import json
import math
import os
import random
import statistics
import subprocess
import sys

import casadi as ca
import yaml

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
from casadi_hs import INF, load_params, model  # noqa: E402

DEGREE = 3
IPOPT = {"max_iter": 1500, "tol": 1e-8, "print_level": 0, "sb": "yes", "linear_solver": "mumps",
         "nlp_scaling_method": "none", "mu_strategy": "monotone", "mu_init": 1e-2}


def radau():
    """Collocation times (0 and the Radau points), the derivative matrix C[j][r]
    (d/dtau of basis j at tau_r) and the quadrature weights B[j]."""
    tau = [0.0] + list(ca.collocation_points(DEGREE, "radau"))
    C = [[0.0] * (DEGREE + 1) for _ in range(DEGREE + 1)]
    B = [0.0] * (DEGREE + 1)
    for j in range(DEGREE + 1):
        p = [1.0]                       # basis j's coefficients, low to high
        for r in range(DEGREE + 1):
            if r != j:
                p = [a - b for a, b in zip([0.0] + p, [c * tau[r] for c in p] + [0.0])]
                p = [c / (tau[j] - tau[r]) for c in p]
        dp = [k * p[k] for k in range(1, len(p))]
        for r in range(DEGREE + 1):
            C[j][r] = sum(c * tau[r] ** k for k, c in enumerate(dp))
        B[j] = sum(c / (k + 1) for k, c in enumerate(p))
    return tau, C, B


class Problem:
    """The transcription, built once per robot and mode; ends are parameters."""

    def __init__(self, robot, mode, intervals):
        g, params = load_params(robot)
        self.nx, self.nu, self.f, b, self.full, _, _ = model(mode, params[mode], g)
        self.vmax, self.params, self.N = b["x_hi"][2], params[mode], intervals
        tau, C, B = radau()
        N, d, o = intervals, DEGREE, ca.Opti()
        self.opti, self.T = o, o.variable()
        self.X = [o.variable(self.nx) for _ in range(N * d + 1)]   # X[k d + j]: interval k, point j
        self.U = [o.variable(self.nu) for _ in range(N + 1)]       # at the interval ends
        self.A, self.Z = o.parameter(self.nx), o.parameter(self.nx)
        h, J = self.T / N, 0
        for k in range(N):
            for j in range(1, d + 1):
                u = self.U[k] + tau[j] * (self.U[k + 1] - self.U[k])
                xd, L = self.f(self.X[k * d + j], u)
                o.subject_to(sum(C[r][j] * self.X[k * d + r] for r in range(d + 1)) == h * xd)
                J = J + B[j] * L * h
        o.subject_to(self.X[0] == self.A)
        o.subject_to(self.X[N * d] == self.Z)
        for x in self.X:
            for i in range(self.nx):
                if b["x_lo"][i] > -INF:
                    o.subject_to(o.bounded(b["x_lo"][i], x[i], b["x_hi"][i]))
        for u in self.U:
            o.subject_to(o.bounded(b["u_lo"], u, b["u_hi"]))
        o.subject_to(o.bounded(b["T"][0], self.T, b["T"][1]))
        o.minimize(J)
        o.solver("ipopt", {"print_time": False, "expand": True}, IPOPT)
        self.J = J
        self.s = [(k + tau[j]) / N for k in range(N) for j in range(d)] + [1.0]   # state times / T
        # The replay's step: one interval of duration dt, the input linear from u0 to u1, the cost appended.
        x, u0, u1 = ca.SX.sym("x", self.nx + 1), ca.SX.sym("u0", self.nu), ca.SX.sym("u1", self.nu)
        dt, t = ca.SX.sym("dt"), ca.SX.sym("t")
        xd, L = self.f(x[:self.nx], u0 + (u1 - u0) * t)
        self.step = ca.integrator("step", "cvodes", {"x": x, "p": ca.vertcat(u0, u1, dt), "t": t,
                                                       "ode": dt * ca.vertcat(xd, L)},
                                  0, 1, {"abstol": 1e-10, "reltol": 1e-10, "max_num_steps": 100000})

    def guess(self, a, z, rng, kind):
        """A start's duration and state at time fraction s: a straight line, or a
        cubic between the ends leaving and arriving forwards or in reverse, the
        heading along its tangent and the end headings blended in."""
        dist = math.hypot(z[0] - a[0], z[1] - a[1])
        if kind == "line":
            T = rng.choice([0.5, 1, 2, 4]) * max(dist, 0.5) / (0.5 * self.vmax) * rng.uniform(0.7, 1.3)
            return T, lambda s: [a[i] + s * (z[i] - a[i]) for i in range(self.nx)]
        d0 = rng.choice([1, -1]) if kind == "random" else (1 if kind == "forward" else -1)
        d1 = rng.choice([1, -1]) if kind == "random" else d0
        k0, k1 = (rng.uniform(0.3, 2.0) * max(dist, 0.5) for _ in range(2))
        t0 = [d0 * k0 * math.cos(a[4]), d0 * k0 * math.sin(a[4])]
        t1 = [d1 * k1 * math.cos(z[4]), d1 * k1 * math.sin(z[4])]
        n = 200
        pos, tan = [], []
        for i in range(n + 1):
            s = i / n
            h = (2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2)
            dh = (6 * s**2 - 6 * s, 3 * s**2 - 4 * s + 1, -6 * s**2 + 6 * s, 3 * s**2 - 2 * s)
            pos.append([h[0] * a[c] + h[1] * t0[c] + h[2] * z[c] + h[3] * t1[c] for c in range(2)])
            tan.append([dh[0] * a[c] + dh[1] * t0[c] + dh[2] * z[c] + dh[3] * t1[c] for c in range(2)])
        length = sum(math.dist(pos[i], pos[i + 1]) for i in range(n))
        T = max(0.3, length / (rng.uniform(0.2, 0.9) * self.vmax) + rng.uniform(0, 2))
        sign = [d0 if i < n / 2 else d1 for i in range(n + 1)]
        th, prev = [], a[4]
        for i in range(n + 1):
            tx, ty = tan[i]
            ang = math.atan2(sign[i] * ty, sign[i] * tx) if math.hypot(tx, ty) > 1e-9 else prev
            ang += 2 * math.pi * round((prev - ang) / (2 * math.pi))
            th.append(ang)
            prev = ang
        e0, e1 = a[4] - th[0], z[4] - th[-1]
        th = [t + (1 - i / n) * e0 + i / n * e1 for i, t in enumerate(th)]

        def state(s):
            i = min(int(s * n), n - 1)
            w = s * n - i
            x = list(a)
            x[0] = pos[i][0] + w * (pos[i + 1][0] - pos[i][0])
            x[1] = pos[i][1] + w * (pos[i + 1][1] - pos[i][1])
            x[4] = th[i] + w * (th[i + 1] - th[i])
            v = max(min(sign[i] * math.hypot(*tan[i]) / T, self.vmax), -self.vmax)
            x[2], x[3] = v, 0.0
            x[5] = max(min((th[i + 1] - th[i]) * n / T, 1.9), -1.9)
            if self.nx == 8:      # marine: propellers at the speed's steady state
                x[6] = x[7] = math.sqrt(self.params["dx"] / (2 * self.params["kT"])) * v
            return x
        return T, state

    def solve(self, x1s, x2s, starts, seed):
        """The cheapest converged start: (cost, T, control at the interval ends), and how many converged."""
        o = self.opti
        a, z = self.full(x1s), self.full(x2s)
        o.set_value(self.A, a)
        o.set_value(self.Z, z)
        rng = random.Random(seed)
        kinds = ["line"] * 4 + ["forward"] * 4 + ["reverse"] * 4 + ["random"] * max(0, starts - 12)
        best, converged = None, 0
        for kind in kinds[:starts]:
            T, state = self.guess(a, z, rng, kind)
            o.set_initial(self.T, T)
            for x, s in zip(self.X, self.s):
                o.set_initial(x, state(s))
            for u in self.U:
                o.set_initial(u, [0] * self.nu)
            try:
                sol = o.solve()
            except RuntimeError:
                continue
            converged += 1
            cost = float(sol.value(self.J))
            if best is None or cost < best[0]:
                best = (cost, float(sol.value(self.T)),
                        [[float(v) for v in ca.vertsplit(ca.DM(sol.value(u)))] for u in self.U])
        return best, converged

    def replay(self, x1s, x2s, T, U):
        """CVODE under the control linear between the interval ends: (cost, largest end-state error)."""
        xs = self.full(x1s) + [0.0]
        for k in range(self.N):
            xs = self.step(x0=xs, p=U[k] + U[k + 1] + [T / self.N])["xf"]
        xs = [float(v) for v in ca.vertsplit(xs)]
        z = self.full(x2s)
        return xs[self.nx], max(abs(xs[i] - z[i]) for i in range(self.nx))


def draw(smp, rng):
    """A pair as the training draw makes them: start at the origin facing +x, the
    goal within the parameter file's distance, any heading, speeds from its range
    (at rest with probability 0.2); smp is the mode's `sampling` entry."""
    r = rng.uniform(0.5, smp["max_distance_m"])
    phi, psi = rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi, math.pi)

    def speed():
        return 0.0 if rng.random() < 0.2 else round(rng.uniform(smp["speed_min_mps"], smp["speed_max_mps"]), 4)
    return [0.0, 0.0, speed(), 0.0], [round(r * math.cos(phi), 4), round(r * math.sin(phi), 4), speed(), round(psi, 4)]


def trainer(robot, mode, x1s, x2s, segments):
    cmd = ["build/bin/trainer", "--robot", robot, "--mode", mode, "--solve", ",".join(map(repr, x1s)),
           ",".join(map(repr, x2s)), "--json", "--segments", str(segments)]
    out = subprocess.run(cmd, capture_output=True, text=True)
    try:
        d = json.loads(out.stdout)
    except ValueError:
        return {"converged": False, "error": out.stderr.strip()[-300:]}
    return {k: d[k] for k in ("converged", "status", "cost_j", "replay_cost_j", "T_s", "segments", "solve_s")}


def percent(a, b):
    return (a / b - 1) * 100


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("robot", help="trainer/params/ROBOT.yaml")
    ap.add_argument("mode", choices=["ground", "marine"])
    ap.add_argument("out", help="results, a JSON line per problem (appended; problems there are skipped)")
    ap.add_argument("--problems", type=int, default=20, help="pairs drawn (default: 20)")
    ap.add_argument("--seed", type=int, default=2026, help="seed of the draw and the starts (default: 2026)")
    ap.add_argument("--starts", type=int, default=30, help="random starts of the independent solve (default: 30)")
    ap.add_argument("--intervals", type=int, default=40, help="its collocation intervals (default: 40)")
    ap.add_argument("--segments", default="20", help="the trainer's meshes, comma-separated (default: 20)")
    ap.add_argument("--reuse", help="an earlier OUT of the same draw: its independent optima are taken, "
                    "only the trainer solves again")
    a = ap.parse_args()
    segments = [int(s) for s in a.segments.split(",")]
    done, reuse = set(), {}
    if a.reuse:
        reuse = {r["problem"]: r for r in map(json.loads, open(a.reuse))}
    if os.path.exists(a.out):
        done = {json.loads(line)["problem"] for line in open(a.out)}
    rng = random.Random(a.seed)
    with open(f"trainer/params/{a.robot}.yaml") as f:
        sampling = yaml.safe_load(f)["modes"][a.mode]["sampling"]
    problems = [draw(sampling, rng) for _ in range(a.problems)]
    P = Problem(a.robot, a.mode, a.intervals)
    with open(a.out, "a") as out:
        for i, (x1s, x2s) in enumerate(problems):
            if i in done:
                continue
            old = reuse.get(i)
            if old:
                if (old["x1"], old["x2"], old["starts"], old["intervals"]) != (x1s, x2s, a.starts, a.intervals):
                    sys.exit(f"{a.reuse}: problem {i} is not this draw's (other --seed, --starts or --intervals)")
                rec = {k: v for k, v in old.items() if k != "trainer"}
                best = (rec["cost_j"], rec["T_s"]) if "cost_j" in rec else None
                converged, rc = rec["converged_starts"], rec.get("replay_cost_j")
            else:
                best, converged = P.solve(x1s, x2s, a.starts, a.seed * 1000 + i)
                rec = {"problem": i, "x1": x1s, "x2": x2s, "starts": a.starts, "converged_starts": converged,
                       "intervals": a.intervals}
                if best:
                    rc, err = P.replay(x1s, x2s, best[1], best[2])
                    rec.update(cost_j=best[0], T_s=best[1], replay_cost_j=rc, replay_error=err)
            rec["trainer"] = {str(s): trainer(a.robot, a.mode, x1s, x2s, s) for s in segments}
            out.write(json.dumps(rec) + "\n")
            out.flush()
            line = f"{i:3d} {x1s} -> {x2s}: independent "
            line += f"{best[0]:.3f} J (replayed {rc:.3f}, {converged}/{a.starts} starts)" if best else "none"
            for s in segments:
                t = rec["trainer"][str(s)]
                line += f"; trainer {s}: " + (f"{t['cost_j']:.3f} J ({percent(t['cost_j'], best[0]):+.2f}%)"
                                              if t["converged"] and best else "none")
            print(line, flush=True)
    recs = [json.loads(line) for line in open(a.out)]
    for s in segments:
        for key, how in (("cost_j", ""), ("replay_cost_j", ", replayed,")):
            gaps = [percent(r["trainer"][str(s)][key], r[key]) for r in recs
                    if key in r and r["trainer"][str(s)]["converged"]]
            if gaps:
                print(f"trainer at {s} segments{how} against the independent optimum{how.rstrip(',')} "
                      f"({len(gaps)} problems): median {statistics.median(gaps):+.2f}%, largest "
                      f"{max(gaps):+.2f}%, smallest {min(gaps):+.2f}%, above +0.5%: {sum(g > 0.5 for g in gaps)}")


if __name__ == "__main__":
    main()
