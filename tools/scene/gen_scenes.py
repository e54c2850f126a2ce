#!/usr/bin/env python3
"""Seeded scene generator: scene files (scenes/README.md) the smoother was
never tuned on.

    tools/scene/gen_scenes.py --robot ambot|drivocopter --seed S [--count N] --out DIR

writes DIR/gen_<robot>_<seed>.yaml for seeds S .. S + N - 1. A scene depends
on its robot and seed only (Python's random.Random seeded with the string
"<robot>:<seed>"), so the same command writes the same bytes anywhere.

Ambot maps (0.5 m cells, 20 x 16, 30 x 24 or 40 x 30 m): one water body (a
lake, a river across the map, or a lake with an island), sometimes a land
bridge across the water or from one shore (stopping short of the other), and
up to three obstacles (rocks and walls, 1 m high). Drivocopter terrain
(0.5 m cells, 30 x 10, 50 x 10 or 40 x 20 m): two or three platforms 2 to
6 m high, the ground between them a chasm floor at 0 m, sometimes a
drivable step (0.1 m) or a wall (1 m) on a platform. Start and goal are
ground states at rest, on level ground with a clear cell around them, at
least a third of the map's width apart.
"""
import argparse
import math
import os
import random
import sys

AMBOT_SIZES = [(20, 16), (30, 24), (40, 30)]
DRIVO_SIZES = [(30, 10), (50, 10), (40, 20)]
RES = 0.5


def r1(x):
    """Rounded to 0.1 (shapes land on a tenth of a metre, bytes stay short)."""
    return round(x * 10) / 10


class Grid:
    """The cells the shapes paint, to place start and goal (hylo-scene does the
    real painting from the YAML: a cell takes the last shape holding its centre)."""

    def __init__(self, w, h, default="ground", height=0.0):
        self.nx, self.ny = int(round(w / RES)), int(round(h / RES))
        self.cls = [[default] * self.nx for _ in range(self.ny)]
        self.h = [[height] * self.nx for _ in range(self.ny)]

    def paint(self, shape):
        for iy in range(self.ny):
            cy = (iy + 0.5) * RES
            for ix in range(self.nx):
                cx = (ix + 0.5) * RES
                if shape["type"] == "rect":
                    inside = shape["x_m"][0] <= cx < shape["x_m"][1] and shape["y_m"][0] <= cy < shape["y_m"][1]
                else:
                    inside = math.hypot(cx - shape["center_m"][0], cy - shape["center_m"][1]) <= shape["radius_m"]
                if inside:
                    self.cls[iy][ix] = shape["class"]
                    self.h[iy][ix] = shape.get("height_m", 0.0)

    def level_ground(self, x, y, clear=1.0):
        """Ground at (x, y) and everywhere within clear of it, at one height."""
        ix, iy = int(x / RES), int(y / RES)
        if not (0 <= ix < self.nx and 0 <= iy < self.ny) or self.cls[iy][ix] != "ground":
            return False
        k = int(math.ceil(clear / RES))
        h0 = self.h[iy][ix]
        for jy in range(iy - k, iy + k + 1):
            for jx in range(ix - k, ix + k + 1):
                if not (0 <= jx < self.nx and 0 <= jy < self.ny):
                    return False
                if self.cls[jy][jx] != "ground" or abs(self.h[jy][jx] - h0) > 1e-6:
                    return False
        return True


def rect(cls, x, y, h=None):
    s = {"type": "rect", "class": cls, "x_m": [r1(x[0]), r1(x[1])], "y_m": [r1(y[0]), r1(y[1])]}
    if h is not None:
        s["height_m"] = h
    return s


def disc(cls, c, r, h=None):
    s = {"type": "disc", "class": cls, "center_m": [r1(c[0]), r1(c[1])], "radius_m": r1(r)}
    if h is not None:
        s["height_m"] = h
    return s


def ambot_shapes(rng, w, h):
    shapes, kind = [], rng.choice(["lake", "river", "island", "lake_bridge"])
    if kind == "river" or (kind == "lake_bridge" and rng.random() < 0.5):
        x0 = rng.uniform(0.3, 0.55) * w
        width = rng.uniform(0.15, 0.3) * w
        shapes.append(rect("water", (x0, x0 + width), (0, h)))
        water = (x0, x0 + width, 0, h)
    else:
        # Half the lakes reach the map's edge (south, north): no way round.
        x0, y0 = rng.uniform(0.2, 0.35) * w, rng.uniform(0.0, 0.25) * h if rng.random() < 0.5 else 0.0
        x1, y1 = rng.uniform(0.65, 0.8) * w, rng.uniform(0.7, 1.0) * h if rng.random() < 0.5 else h
        if rng.random() < 0.5:
            shapes.append(rect("water", (x0, x1), (y0, y1)))
        else:
            shapes.append(disc("water", ((x0 + x1) / 2, (y0 + y1) / 2), min(x1 - x0, y1 - y0) / 2))
        water = (x0, x1, y0, y1)
    if kind == "island":
        cx, cy = (water[0] + water[1]) / 2, (water[2] + water[3]) / 2
        r = 0.2 * min(water[1] - water[0], water[3] - water[2])
        shapes.append(disc("ground", (cx + rng.uniform(-1, 1), cy + rng.uniform(-2, 2)), max(1.5, r)))
    if kind == "lake_bridge" or (kind == "river" and rng.random() < 0.3):
        # A land bridge across the water, 2 to 3 m wide; sometimes from one
        # shore only, stopping 1.5 to 3 m short of the other (a short swim).
        yb = rng.uniform(water[2] + 1, water[3] - 3)
        gap = rng.uniform(1.5, 3.0) if rng.random() < 0.6 else 0.0
        xa, xb = water[0], water[1]
        if gap:
            if rng.random() < 0.5:
                xa += gap
            else:
                xb -= gap
        shapes.append(rect("ground", (xa, xb), (yb, yb + rng.uniform(2, 3))))
    for _ in range(rng.randint(0, 3)):
        if rng.random() < 0.6:
            shapes.append(disc("obstacle", (rng.uniform(0, w), rng.uniform(0, h)), rng.uniform(0.8, 2.0), 1.0))
        else:
            x, y = rng.uniform(0, w), rng.uniform(0, h)
            if rng.random() < 0.5:
                shapes.append(rect("obstacle", (x, x + 0.5), (y, y + rng.uniform(2, 5)), 1.0))
            else:
                shapes.append(rect("obstacle", (x, x + rng.uniform(2, 5)), (y, y + 0.5), 1.0))
    return kind, shapes


def drivo_shapes(rng, w, h):
    shapes, n = [], rng.choice([2, 2, 3])
    kind = "platforms" if n == 2 else "three_platforms"
    # Platforms along x with chasms (floor at 0 m) between them.
    widths = [rng.uniform(0.2, 0.3) * w for _ in range(n)]
    gaps = [rng.uniform(0.1, 0.3) * w for _ in range(n - 1)]
    scale = min(1.0, w / (sum(widths) + sum(gaps)))
    x = 0.0
    for i in range(n):
        x1 = w if i == n - 1 else x + widths[i] * scale
        shapes.append(rect("ground", (x, x1), (0, h), r1(rng.uniform(2, 6))))
        if i < n - 1:
            x = x1 + gaps[i] * scale
    if rng.random() < 0.5:
        # A step on the first platform: drivable (0.1 m) or a wall (1 m).
        p = shapes[0]
        xs = r1(rng.uniform(p["x_m"][0] + 2, p["x_m"][1] - 1))
        up = 0.1 if rng.random() < 0.5 else 1.0
        shapes.append(rect("ground", (xs, p["x_m"][1]), (0, h), r1(p["height_m"] + up)))
        kind += "_step" if up < 0.5 else "_wall"
    return kind, shapes


def place(rng, grid, w, h):
    """Start and goal: level ground with a clear metre around, far apart."""
    def spot(xlo, xhi):
        for _ in range(2000):
            x, y = r1(rng.uniform(xlo, xhi)), r1(rng.uniform(1, h - 1))
            if grid.level_ground(x, y):
                return x, y
        return None
    a, b = spot(0.5, 0.3 * w), spot(0.7 * w, w - 0.5)
    if a and b and math.hypot(b[0] - a[0], b[1] - a[1]) >= w / 3:
        return a, b
    return None


def scene_yaml(robot, seed, rng):
    for attempt in range(50):
        if robot == "ambot":
            w, h = rng.choice(AMBOT_SIZES)
            kind, shapes = ambot_shapes(rng, w, h)
        else:
            w, h = rng.choice(DRIVO_SIZES)
            kind, shapes = drivo_shapes(rng, w, h)
        grid = Grid(w, h)
        for s in shapes:
            grid.paint(s)
        ends = place(rng, grid, w, h)
        if ends:
            break
    else:
        raise SystemExit(f"gen_scenes: no start and goal found for {robot} seed {seed}")
    (sx, sy), (gx, gy) = ends
    nx, ny = int(round(w / RES)), int(round(h / RES))

    def shape_line(s):
        parts = [f"type: {s['type']}", f"class: {s['class']}"]
        for k in ("x_m", "y_m", "center_m"):
            if k in s:
                parts.append(f"{k}: [{s[k][0]:g}, {s[k][1]:g}]")
        for k in ("radius_m", "height_m"):
            if k in s:
                parts.append(f"{k}: {s[k]:g}")
        return "    - {" + ", ".join(parts) + "}"

    name = f"gen_{robot}_{seed}"
    lines = [f"name: {name}",
             f"description: generated by tools/scene/gen_scenes.py --robot {robot} --seed {seed} ({kind}, {w} m x {h} m)",
             f"robot: {robot}",
             f"map_id: {seed + 1}",
             f"grid: {{nx: {nx}, ny: {ny}, resolution_m: {RES}, origin_m: [0, 0]}}"]
    if robot == "ambot":
        lines += ["max_step_m: 0.1"]
    else:
        lines += ["ceiling_m: 20", "max_step_m: 0.2"]
    lines += ["terrain:", "  default: ground", "  shapes:"] + [shape_line(s) for s in shapes]
    lines += ["goal:",
              f"  start: {{mode: ground, state: [{sx:g}, {sy:g}, 0, 0]}}",
              f"  goal: {{mode: ground, state: [{gx:g}, {gy:g}, 0, 0]}}",
              "  seed: 1",
              "  spacing_m: 2.0",
              "  guard_spacing_m: 2.0",
              "  connect_radius_m: 4.5"]
    if robot == "ambot":
        lines += ["  speeds_mps: [0.0, 0.5, 1.0]",
                  "  headings_rad: [0, 0.785398, 1.570796, 2.356194, 3.141593, -2.356194, -1.570796, -0.785398]"]
    else:
        lines += ["  air_spacing_m: 4.0",
                  "  air_connect_radius_m: 9.0",
                  "  speeds_mps: [0.0, 1.0, 2.0]",
                  "  headings_rad: [0, 3.141593]",
                  "  air_speeds_mps: [0.0, 4.0, 8.0]"]
    return name, "\n".join(lines) + "\n"


def main(argv):
    ap = argparse.ArgumentParser(description="Writes seeded scene files (see the module docstring).")
    ap.add_argument("--robot", required=True, choices=["ambot", "drivocopter"])
    ap.add_argument("--seed", type=int, default=1, help="first seed (default 1)")
    ap.add_argument("--count", type=int, default=1, help="scenes, seeds seed .. seed + count - 1 (default 1)")
    ap.add_argument("--out", required=True, help="directory to write the scenes into")
    a = ap.parse_args(argv)
    if a.count < 1 or a.seed < 0:
        ap.error("--count must be >= 1 and --seed >= 0")
    os.makedirs(a.out, exist_ok=True)
    for seed in range(a.seed, a.seed + a.count):
        name, text = scene_yaml(a.robot, seed, random.Random(f"{a.robot}:{seed}"))
        path = os.path.join(a.out, name + ".yaml")
        with open(path, "w") as f:
            f.write(text)
        print(path)


if __name__ == "__main__":
    main(sys.argv[1:])
