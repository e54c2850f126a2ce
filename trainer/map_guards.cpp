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

std::vector<WallCrossing> wall_crossings(const TerrainGrid &m, const double *a, const double *b)
{
	std::vector<WallCrossing> out;
	double len = std::hypot(b[0] - a[0], b[1] - a[1]);
	int steps = std::max(1, static_cast<int>(std::ceil(4 * len / m.resolution_m)));
	GridCell prev = cell_at(m, a[0], a[1]);
	for (int i = 1; i <= steps && prev.inside; i++) {
		double t = static_cast<double>(i) / steps;
		GridCell c = cell_at(m, a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
		if (!c.inside || c.index == prev.index) {
			prev = c;
			continue;
		}
		double h0 = m.height_m[static_cast<size_t>(prev.index)], h1 = m.height_m[static_cast<size_t>(c.index)];
		if (std::fabs(h1 - h0) > m.max_step_m) {
			int ix0 = prev.index % m.nx, ix1 = c.index % m.nx, iy0 = prev.index / m.nx, iy1 = c.index / m.nx;
			WallGate g;
			g.axis = ix0 != ix1 ? 0 : 1;
			g.c = g.axis == 0 ? m.origin_x_m + std::max(ix0, ix1) * m.resolution_m
					  : m.origin_y_m + std::max(iy0, iy1) * m.resolution_m;
			g.z_min = std::max(h0, h1) + kAirClearanceM;
			double d = b[g.axis] - a[g.axis];
			out.push_back({std::fabs(d) > 1e-12 ? (g.c - a[g.axis]) / d : t, g});
		}
		prev = c;
	}
	return out;
}

}  // namespace hylo::trainer
