#include "trainer/map_guards.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace hylo::trainer {
namespace {

struct Point {
	double x, y;
};

// Midpoints of the edges between ground and water cells within r of (x, y).
std::vector<Point> shore_points(const TerrainGrid &m, double x, double y, double r)
{
	std::vector<Point> pts;
	int cx = static_cast<int>((x - m.origin_x_m) / m.resolution_m);
	int cy = static_cast<int>((y - m.origin_y_m) / m.resolution_m);
	int span = static_cast<int>(std::ceil(r / m.resolution_m)) + 1;
	for (int iy = std::max(0, cy - span); iy <= std::min(m.ny - 1, cy + span); iy++)
		for (int ix = std::max(0, cx - span); ix <= std::min(m.nx - 1, cx + span); ix++) {
			int8_t t = m.terrain[static_cast<size_t>(iy * m.nx + ix)];
			const int nb[2][2] = {{1, 0}, {0, 1}};
			for (const auto &d : nb) {
				int jx = ix + d[0], jy = iy + d[1];
				if (jx >= m.nx || jy >= m.ny)
					continue;
				int8_t u = m.terrain[static_cast<size_t>(jy * m.nx + jx)];
				if (!((t == kGround && u == kWater) || (t == kWater && u == kGround)))
					continue;
				Point p{m.origin_x_m + (ix + 0.5 + 0.5 * d[0]) * m.resolution_m,
					m.origin_y_m + (iy + 0.5 + 0.5 * d[1]) * m.resolution_m};
				if (std::hypot(p.x - x, p.y - y) <= r)
					pts.push_back(p);
			}
		}
	return pts;
}

}  // namespace

SwitchGuard shoreline_guard(const TerrainGrid &m, double x, double y, double half_length)
{
	double fit_r = std::max(1.5, 3 * m.resolution_m);
	std::vector<Point> near = shore_points(m, x, y, fit_r);
	if (near.size() < 2)
		throw std::invalid_argument("no shoreline near the switch point (" + std::to_string(x) + ", " +
					    std::to_string(y) + ")");
	double mx = 0, my = 0;
	for (const Point &p : near) {
		mx += p.x;
		my += p.y;
	}
	mx /= static_cast<double>(near.size());
	my /= static_cast<double>(near.size());
	double sxx = 0, sxy = 0, syy = 0;
	for (const Point &p : near) {
		sxx += (p.x - mx) * (p.x - mx);
		sxy += (p.x - mx) * (p.y - my);
		syy += (p.y - my) * (p.y - my);
	}
	double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
	double tx = std::cos(angle), ty = std::sin(angle);
	std::vector<Point> shore = shore_points(m, x, y, half_length + m.resolution_m);
	auto on_shore = [&](double px, double py) {
		for (const Point &p : shore)
			if (std::hypot(p.x - px, p.y - py) <= m.resolution_m)
				return true;
		return false;
	};
	double step = 0.5 * m.resolution_m, ends[2] = {0, 0};
	for (int side = 0; side < 2; side++) {
		double sgn = side ? 1.0 : -1.0;
		for (double s = step; s <= half_length + 1e-9 && on_shore(x + sgn * s * tx, y + sgn * s * ty); s += step)
			ends[side] = s;
	}
	return {x - ends[0] * tx, y - ends[0] * ty, x + ends[1] * tx, y + ends[1] * ty, 0};
}

namespace {

// The rectangle of level, drivable ground around (x, y) (clear_platform):
// grown a row or column of cells at a time while the new cells are level with
// (x, y)'s and within half_length of it. With clear, only its clear ground
// cells count (the takeoff cell's too).
SwitchGuard platform_area(const TerrainGrid &m, double x, double y, double half_length,
			  const ClearanceMap *clear = nullptr)
{
	GridCell c = cell_at(m, x, y);
	if (!c.inside || m.terrain[static_cast<size_t>(c.index)] != kGround)
		throw std::invalid_argument("the takeoff or landing point (" + std::to_string(x) + ", " +
					    std::to_string(y) + ") is not on drivable ground");
	const double h = m.height_m[static_cast<size_t>(c.index)];
	const int cx = c.index % m.nx, cy = c.index / m.nx;
	const int reach = static_cast<int>(std::floor(half_length / m.resolution_m + 1e-9));
	auto level = [&](int ix, int iy) {
		size_t k = static_cast<size_t>(iy * m.nx + ix);
		return m.terrain[k] == kGround && std::fabs(m.height_m[k] - h) < 1e-3 &&
		       (!clear || clear->clear(HYLO_MODE_GROUND, ix, iy));
	};
	int lo[2] = {cx, cy}, hi[2] = {cx, cy};
	const int size[2] = {m.nx, m.ny}, centre[2] = {cx, cy};
	for (bool grew = true; grew;) {
		grew = false;
		for (int axis = 0; axis < 2; axis++)
			for (int dir = -1; dir <= 1; dir += 2) {
				int at = (dir < 0 ? lo[axis] : hi[axis]) + dir;
				if (at < 0 || at >= size[axis] || std::abs(at - centre[axis]) > reach)
					continue;
				bool ok = true;
				int other = 1 - axis;
				for (int j = lo[other]; j <= hi[other] && ok; j++)
					ok = axis == 0 ? level(at, j) : level(j, at);
				if (ok) {
					(dir < 0 ? lo[axis] : hi[axis]) = at;
					grew = true;
				}
			}
	}
	SwitchGuard g;
	g.area = true;
	g.height_m = h;
	g.ax = std::min(x, m.origin_x_m + (lo[0] + 0.5) * m.resolution_m);
	g.bx = std::max(x, m.origin_x_m + (hi[0] + 0.5) * m.resolution_m);
	g.ay = std::min(y, m.origin_y_m + (lo[1] + 0.5) * m.resolution_m);
	g.by = std::max(y, m.origin_y_m + (hi[1] + 0.5) * m.resolution_m);
	return g;
}

}  // namespace

bool shore_from_boxes(const CorridorBox &a, const CorridorBox &b, double x, double y, double half_length,
		      SwitchGuard &g)
{
	double lo[2], hi[2], at[2] = {x, y};
	for (int i = 0; i < 2; i++) {
		lo[i] = std::max({a.lo[static_cast<size_t>(i)], b.lo[static_cast<size_t>(i)], at[i] - half_length});
		hi[i] = std::min({a.hi[static_cast<size_t>(i)], b.hi[static_cast<size_t>(i)], at[i] + half_length});
		if (lo[i] > hi[i])
			return false;
	}
	g = SwitchGuard{lo[0], lo[1], hi[0], hi[1], 0};
	g.area = true;
	return true;
}

SwitchGuard clear_platform(const TerrainGrid &map, double x, double y, double half_length, const CorridorMaps *maps,
			   std::vector<std::string> &notes)
{
	if (!maps)
		return platform_area(map, x, y, half_length);
	GridCell c = cell_at(map, x, y);
	for (const auto &level : maps->levels())
		if (c.inside && level->clear(HYLO_MODE_GROUND, c.index % map.nx, c.index / map.nx)) {
			if (level->clearance() < maps->levels().front()->clearance()) {
				char buf[160];
				std::snprintf(buf, sizeof buf, "switch at (%.3g, %.3g): its cell is clear by %.3g m, not %.3g m",
					      x, y, level->clearance(), maps->levels().front()->clearance());
				notes.push_back(buf);
			}
			return platform_area(map, x, y, half_length, level.get());
		}
	return platform_area(map, x, y, half_length);
}

namespace {

// The cells of columns x0..x1, rows y0..y1.
struct CellBox {
	int32_t x0, x1, y0, y1;
	bool holds(const CellBox &c) const { return c.x0 >= x0 && c.x0 <= x1 && c.y0 >= y0 && c.y0 <= y1; }
};

}  // namespace

std::vector<WallCrossing> wall_crossings(const TerrainGrid &m, const double *a, const double *b)
{
	const double o[2] = {m.origin_x_m, m.origin_y_m}, r = m.resolution_m;
	const double ua[2] = {(a[0] - o[0]) / r, (a[1] - o[1]) / r}, ub[2] = {(b[0] - o[0]) / r, (b[1] - o[1]) / r};
	// The flight floor over some cells: their highest (map.c: a point on a
	// grid line is over every cell it touches).
	auto highest = [&](const CellBox &c) {
		double h = -HUGE_VAL;
		for (int32_t iy = c.y0; iy <= c.y1; iy++)
			for (int32_t ix = c.x0; ix <= c.x1; ix++)
				h = std::max(h, static_cast<double>(m.height_m[static_cast<size_t>(iy * m.nx + ix)]));
		return h;
	};
	auto touching = [&](const double *u) {
		CellBox c;
		hylo_cell_span(u[0], m.nx, &c.x0, &c.x1);
		hylo_cell_span(u[1], m.ny, &c.y0, &c.y1);
		return c;
	};
	std::vector<WallCrossing> out;
	// from -> to across grid line u = line_u (or v = line_v), at a point
	// over the cells at: a wall where the floor there and one side's differ
	// by more than max_step.
	auto cross = [&](double t, const CellBox &from, const CellBox &to, const CellBox &at, int32_t line_u,
			 int32_t line_v) {
		const double h = highest(at);
		if (h - std::min(highest(from), highest(to)) <= m.max_step_m)
			return;
		WallGate g;
		g.axis = line_u >= 0 ? 0 : 1;   // through a vertex: its x line
		g.c = o[g.axis] + (g.axis == 0 ? line_u : line_v) * r;
		g.z_min = h + kAirClearanceM;
		out.push_back({t, g});
	};
	// An end on a grid line is in the cell cell_at gives it, so that a flight
	// through a waypoint on a wall's line is cut once: at the end of the edge
	// that reaches that cell, or at the start of the one that leaves it.
	auto end_cell = [&](const double *p, CellBox &c) {
		const GridCell g = cell_at(m, p[0], p[1]);
		c = {g.index % m.nx, g.index % m.nx, g.index / m.nx, g.index / m.nx};
		return g.inside;
	};
	auto line_between = [](int32_t c, int32_t lo, int32_t hi) { return c < lo ? lo : c > hi ? c : -1; };
	hylo_cell_walk w;
	hylo_cell_walk_start(&w, m.nx, m.ny, ua[0], ua[1], ub[0], ub[1]);
	hylo_cell_piece p, q;
	CellBox end;
	if (!hylo_cell_walk_next(&w, &p))
		return out;
	CellBox pc{p.x0, p.x1, p.y0, p.y1};
	if (end_cell(a, end) && !pc.holds(end))
		cross(0, end, pc, touching(ua), line_between(end.x0, p.x0, p.x1), line_between(end.y0, p.y0, p.y1));
	for (; hylo_cell_walk_next(&w, &q); p = q, pc = {p.x0, p.x1, p.y0, p.y1})
		cross(p.t1, pc, {q.x0, q.x1, q.y0, q.y1}, {p.ex0, p.ex1, p.ey0, p.ey1}, p.cross_u, p.cross_v);
	if (w.t >= 1 && end_cell(b, end) && !pc.holds(end))
		cross(1, pc, end, touching(ub), line_between(end.x0, p.x0, p.x1), line_between(end.y0, p.y0, p.y1));
	return out;
}

}  // namespace hylo::trainer
