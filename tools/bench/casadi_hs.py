#!/usr/bin/env python3
"""The trainer's bare Hermite-Simpson solves, redone with CasADi (PyPI casadi,
Ipopt inside) for make bench: the same transcription (separated form,
piecewise-linear input, same segments, bounds, initial guess, T guess,
scaling, tolerance and Ipopt options) of docs/models.md's dynamics, written here a
second time in CasADi's symbolic expressions. Reads the BVPs and hylo's
figures that bench_trainer wrote, prints a table, writes result rows.

usage: casadi_hs.py BARE_SOLVES.json RESULTS.json
"""
import json
import math
import statistics
import sys
import time

import casadi as ca
import yaml


def load_params(robot):
    with open(f"trainer/params/{robot}.yaml") as f:
        y = yaml.safe_load(f)
    return y["g"], {m: v["params"] for m, v in y["modes"].items()}


def pos_power(P):   # docs/models.md section 1, relax 1
    return (P + ca.sqrt(P * P + 0.1 ** 2)) * 0.5


def signed_square(x):
    return x * ca.sqrt(x * x + 1e-3 ** 2)


INF = 1e20


def model(mode, p, g):
    """(nx, nu, f(x, u) -> (xdot, L), bounds, full_state, x scale, u guess)."""
    if mode in ("di_neg", "di_pos"):
        pos = mode == "di_pos"

        def f(x, u):
            return ca.vertcat(x[1], u[0] - x[1] if pos else u[0]), u[0] ** 2 + p["rho"]
        b = dict(x_lo=[0 if pos else -1, -1], x_hi=[1 if pos else 0, 1], u_lo=[-1], u_hi=[1], T=(0.05, 20))
        return 2, 1, f, b, lambda xs: list(xs), [1, 1], [0]
    if mode == "ground":
        q = p

        def f(x, u):
            vx, vy, th, om = x[2], x[3], x[4], x[5]
            phiL = q["G"] * (vx - om * (q["B"] / 2)) / q["r"]
            phiR = q["G"] * (vx + om * (q["B"] / 2)) / q["r"]
            VL, VR = q["Vcc"] * u[0], q["Vcc"] * u[1]
            iL, iR = (VL - q["kt"] * phiL) / q["R"], (VR - q["kt"] * phiR) / q["R"]
            FL, FR = q["G"] * q["kt"] * iL / q["r"], q["G"] * q["kt"] * iR / q["r"]
            Fx = FL + FR - q["crr"] * q["m"] * g * ca.tanh(vx / 0.05)
            Fy = -q["Cy"] * vy
            Mz = (FR - FL) * (q["B"] / 2) - q["mut"] * q["m"] * g * q["Lc"] / 4 * ca.tanh(om / 0.1)
            xd = ca.vertcat(vx * ca.cos(th) - vy * ca.sin(th), vx * ca.sin(th) + vy * ca.cos(th),
                            Fx / q["m"] + om * vy, Fy / q["m"] - om * vx, om, Mz / q["Iz"])
            return xd, pos_power(VL * iL) + pos_power(VR * iR) + q["Pd"]
        v = q["vmax"]
        b = dict(x_lo=[-INF, -INF, -v, -1, -INF, -3], x_hi=[INF, INF, v, 1, INF, 3], u_lo=[-1, -1], u_hi=[1, 1], T=(0.1, 60))
        return 6, 2, f, b, lambda xs: [xs[0], xs[1], xs[2], 0, xs[3], 0], [1] * 6, [0, 0]
    if mode == "marine":
        q = p
        c = math.sqrt(q["dx"] / (2 * q["kT"]))

        def f(x, u):
            vx, vy, th, om, pL, pR = x[2], x[3], x[4], x[5], x[6], x[7]
            VL, VR = q["Vcc"] * u[0], q["Vcc"] * u[1]
            iL, iR = (VL - q["kt"] * pL) / q["R"], (VR - q["kt"] * pR) / q["R"]
            TL, TR = q["kT"] * signed_square(pL), q["kT"] * signed_square(pR)
            Fx = TL + TR - q["dx"] * signed_square(vx)
            Fy = -q["dy"] * signed_square(vy) - q["Cy_w"] * vy
            Mz = (TR - TL) * (q["B"] / 2) - q["dw"] * signed_square(om)
            xd = ca.vertcat(vx * ca.cos(th) - vy * ca.sin(th), vx * ca.sin(th) + vy * ca.cos(th),
                            Fx / q["m"] + om * vy, Fy / q["m"] - om * vx, om, Mz / q["Iz"],
                            (q["kt"] * iL - q["kq"] * signed_square(pL)) / q["Jm"],
                            (q["kt"] * iR - q["kq"] * signed_square(pR)) / q["Jm"])
            return xd, pos_power(VL * iL) + pos_power(VR * iR) + q["Pd"]
        v = q["vmax_w"]
        ps = max(1.0, c * v)
        b = dict(x_lo=[-INF, -INF, -v, -1, -INF, -2, -INF, -INF], x_hi=[INF, INF, v, 1, INF, 2, INF, INF],
                 u_lo=[-1, -1], u_hi=[1, 1], T=(0.1, 90))
        return 8, 2, f, b, lambda xs: [xs[0], xs[1], xs[2], 0, xs[3], 0, c * xs[2], c * xs[2]], [1] * 6 + [ps, ps], [0, 0]
    raise ValueError(mode)


def solve(case):
    g, params = load_params(case["robot"])
    nx, nu, f, b, full, sc, ug = model(case["mode"], params[case["mode"]], g)
    N, Tg = case["segments"], case["T_guess"]
    a, z = full(case["x1s"]), full(case["x2s"])
    npts, nz = 2 * N + 1, nx + nu
    # Variables in hylo's scaled units (Ipopt user-scaling there): state k / sc[k], T / max(1, Tg).
    w = ca.SX.sym("w", npts * nz + 1)
    Tsc = max(1.0, Tg)
    def X(p): return ca.vertcat(*[w[p * nz + k] * sc[k] for k in range(nx)])
    def U(p): return ca.vertcat(*[w[p * nz + nx + k] for k in range(nu)])
    T = w[npts * nz] * Tsc
    knot = lambda i: i
    mid = lambda k: N + 1 + k
    F, L = {}, {}
    for p in range(npts):
        F[p], L[p] = f(X(p), U(p))
    h = T / N
    gs = []
    for k in range(N):
        xa, xb, xm = X(knot(k)), X(knot(k + 1)), X(mid(k))
        c1 = xm - 0.5 * (xa + xb) - h / 8 * (F[knot(k)] - F[knot(k + 1)])
        c2 = xb - xa - h / 6 * (F[knot(k)] + 4 * F[mid(k)] + F[knot(k + 1)])
        gs += [c1[r] / sc[r] for r in range(nx)] + [c2[r] / sc[r] for r in range(nx)]
    for k in range(N):
        um, ua, ub = U(mid(k)), U(knot(k)), U(knot(k + 1))
        gs += [um[j] - 0.5 * (ua[j] + ub[j]) for j in range(nu)]
    J = h / 6 * sum((4 if p > N else (1 if p in (0, N) else 2)) * L[p] for p in range(npts))
    obj_scale = 1.0 / max(1.0, Tg * 10.0)
    lbw, ubw, w0 = [], [], []
    for p in range(npts):
        s = p / N if p <= N else (p - N - 1 + 0.5) / N
        for k in range(nx):
            lo, hi = b["x_lo"][k], b["x_hi"][k]
            if p == knot(0):
                lo = hi = a[k]
            elif p == knot(N):
                lo = hi = z[k]
            lbw.append(lo / sc[k] if lo > -INF else -INF)
            ubw.append(hi / sc[k] if hi < INF else INF)
            w0.append(min(max(a[k] + s * (z[k] - a[k]), b["x_lo"][k]), b["x_hi"][k]) / sc[k])
        for k in range(nu):
            lbw.append(b["u_lo"][k])
            ubw.append(b["u_hi"][k])
            w0.append(ug[k])
    lbw.append(b["T"][0] / Tsc)
    ubw.append(b["T"][1] / Tsc)
    w0.append(Tg / Tsc)
    opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes", "ipopt.tol": case["tol"],
            "ipopt.max_iter": 1000, "ipopt.linear_solver": "mumps", "ipopt.mu_strategy": "monotone",
            "ipopt.mu_init": 1e-2, "ipopt.nlp_scaling_method": "none"}
    solver = ca.nlpsol("hs", "ipopt", {"x": w, "f": J * obj_scale, "g": ca.vertcat(*gs)}, opts)
    times, res = [], None
    for _ in range(5):
        t0 = time.perf_counter()
        res = solver(x0=w0, lbx=lbw, ubx=ubw, lbg=0, ubg=0)
        times.append(time.perf_counter() - t0)
    st = solver.stats()
    return {"converged": bool(st["success"]), "seconds": statistics.median(times),
            "iterations": int(st["iter_count"]), "cost": float(res["f"]) / obj_scale,
            "T": float(res["x"][npts * nz]) * Tsc}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    cases = json.load(open(sys.argv[1]))
    rows, by_mode = [], {}
    print(f"bare transcription solves, hylo vs CasADi {ca.__version__} (same Ipopt options), median of 5 each")
    print(f"  {'mode':14} {'hylo s':>9} {'CasADi s':>9} {'hylo it':>8} {'CasADi it':>9} {'cost rel diff':>14}")
    for c in cases:
        r = solve(c)
        h = c["hylo"]
        both = h["converged"] and r["converged"]
        diff = abs(h["cost"] - r["cost"]) / abs(r["cost"]) if both else float("nan")
        print(f"  {c['mode']:14} {h['seconds']:9.4f} {r['seconds']:9.4f} {h['iterations']:8d} {r['iterations']:9d} "
              f"{diff:14.2e}{'' if both else '   (not both converged)'}")
        by_mode.setdefault((c["robot"], c["mode"]), []).append((h, r, diff, both))
    for (robot, mode), items in by_mode.items():
        ok = [it for it in items if it[3]]
        if not ok:
            continue
        hs, cs = statistics.median(i[0]["seconds"] for i in ok), statistics.median(i[1]["seconds"] for i in ok)
        worst = max(i[2] for i in ok)
        ref = f"CasADi {ca.__version__} + Ipopt, same transcription, median over {len(ok)} BVPs"
        rows.append({"name": f"trainer_bare_solve_s_{robot}_{mode}", "value": hs, "unit": "s", "reference": ref,
                     "reference_value": cs, "ratio": cs / hs})
        rows.append({"name": f"trainer_bare_iterations_{robot}_{mode}",
                     "value": statistics.median(i[0]["iterations"] for i in ok), "unit": "iterations",
                     "reference": ref, "reference_value": statistics.median(i[1]["iterations"] for i in ok),
                     "ratio": None})
        rows.append({"name": f"trainer_cost_rel_diff_max_{robot}_{mode}", "value": worst, "unit": "relative",
                     "reference": ref, "reference_value": 0, "ratio": None})
        print(f"  {robot} {mode}: {len(ok)}/{len(items)} both converged; median {hs:.4f} s vs {cs:.4f} s "
              f"({cs / hs:.2f}x); largest cost difference {worst:.1e}")
    json.dump(rows, open(sys.argv[2], "w"), indent=1)


if __name__ == "__main__":
    main()
