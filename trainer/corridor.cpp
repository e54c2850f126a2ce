#include "trainer/corridor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "hylo/clearance.h"
#include "hylo/map.h"

namespace hylo::trainer {

struct ClearanceMap::Map {
	hylo_map m;
};

ClearanceMap::ClearanceMap(const TerrainGrid &g, double r) : m_(std::make_unique<Map>()), r_(r), nx_(g.nx), ny_(g.ny)
{
	if (g.terrain.size() != static_cast<size_t>(g.nx) * static_cast<size_t>(g.ny) ||
	    g.height_m.size() != g.terrain.size())
		throw std::invalid_argument("corridor: the map's terrain and heights are not nx * ny cells");
	double ceiling = g.ceiling_m;
	if (!std::isfinite(ceiling)) {   // no ceiling: far above the highest cell
		float top = g.height_m.empty() ? 0.0f : *std::max_element(g.height_m.begin(), g.height_m.end());
		ceiling = static_cast<double>(top) + 1e4;
	}
	hylo_map_view v{};
	v.robot = "smoother";
	v.nx = g.nx;
	v.ny = g.ny;
	v.resolution = g.resolution_m;
	v.origin_x = g.origin_x_m;
	v.origin_y = g.origin_y_m;
	v.ceiling = ceiling;
	v.max_step = g.max_step_m;
	v.n_cells = g.nx * g.ny;
	v.terrain = g.terrain.data();
	v.height = g.height_m.data();
	hylo_reason why;
	if (hylo_map_ingest(&m_->m, &v, &why) != HYLO_OK || hylo_map_inflate(&m_->m, r, &why) != HYLO_OK)
		throw std::invalid_argument(std::string("corridor: ") + why.text);
}

ClearanceMap::~ClearanceMap() = default;

bool ClearanceMap::clear(const std::string &mode, int ix, int iy) const
{
	hylo_mode md = mode == "ground" ? HYLO_MODE_GROUND : HYLO_MODE_MARINE;
	return hylo_map_cell_clear(&m_->m, md, iy * nx_ + ix) != 0;
}

double ClearanceMap::flight_floor(int ix, int iy) const
{
	double f = hylo_map_flight_floor(&m_->m, iy * nx_ + ix);
	return std::isfinite(f) ? f : std::numeric_limits<double>::infinity();
}

double ClearanceMap::flight_top() const
{
	return hylo_map_flight_top(&m_->m);
}

CorridorMaps::CorridorMaps(const TerrainGrid &grid, double body_and_margin, double pad) : grid_(grid)
{
	for (double r : {body_and_margin + pad, body_and_margin, 0.0})
		if (levels_.empty() || r < levels_.back()->clearance())
			levels_.push_back(std::make_unique<ClearanceMap>(grid, r));
}

namespace {

using P3 = std::array<double, 3>;

// A box of cells [ix0, ix1] x [iy0, iy1] and, for a flight, its heights.
struct CellBox {
	int ix0 = 0, ix1 = -1, iy0 = 0, iy1 = -1;
	double z0 = 0, z1 = 0;
};

// Cell ranges along one axis whose closed squares hold [u0, u1] (grid
// units): the cells the interval's inside crosses, or for a point on a cell
// edge the cell on either side. Cells off the map are dropped.
std::vector<std::pair<int, int>> axis_seeds(double u0, double u1, int n)
{
	constexpr double eps = 1e-9;
	int lo = static_cast<int>(std::floor(u0 + eps)), hi = static_cast<int>(std::ceil(u1 - eps)) - 1;
	std::vector<std::pair<int, int>> out;
	if (hi >= lo)
		out.push_back({lo, hi});
	else
		out = {{lo - 1, lo - 1}, {lo, lo}};
	std::vector<std::pair<int, int>> on_map;
	for (const auto &r : out)
		if (r.first >= 0 && r.second < n)
			on_map.push_back(r);
	return on_map;
}

class Grower {
public:
	Grower(const std::string &mode, const ClearanceMap &m) : mode_(mode), m_(m), flight_(mode == "flight") {}

	// The box of cells around [a, b] (grid units for x and y), grown while
	// clear; false if the cells around the segment are not clear.
	bool grow(const P3 &a, const P3 &b, CellBox &box) const
	{
		zlo_ = std::min(a[2], b[2]);
		zhi_ = std::max(a[2], b[2]);
		if (flight_ && zhi_ > m_.flight_top() + 1e-9)
			return false;
		for (const auto &xs : axis_seeds(std::min(a[0], b[0]), std::max(a[0], b[0]), m_.nx()))
			for (const auto &ys : axis_seeds(std::min(a[1], b[1]), std::max(a[1], b[1]), m_.ny())) {
				CellBox c{xs.first, xs.second, ys.first, ys.second, 0, 0};
				if (!strip_clear(c.ix0, c.ix1, c.iy0, c.iy1))
					continue;
				expand(c);
				box = c;
				return true;
			}
		return false;
	}

private:
	bool cell_ok(int ix, int iy) const
	{
		if (!flight_)
			return m_.clear(mode_, ix, iy);
		return m_.flight_floor(ix, iy) <= zlo_ + 1e-9;
	}

	bool strip_clear(int ix0, int ix1, int iy0, int iy1) const
	{
		if (ix0 < 0 || iy0 < 0 || ix1 >= m_.nx() || iy1 >= m_.ny())
			return false;
		for (int iy = iy0; iy <= iy1; iy++)
			for (int ix = ix0; ix <= ix1; ix++)
				if (!cell_ok(ix, iy))
					return false;
		return true;
	}

	// Round robin over the four sides: a side grows by a row (column) of
	// cells while that row is clear.
	void expand(CellBox &c) const
	{
		bool open[4] = {true, true, true, true};
		while (open[0] || open[1] || open[2] || open[3]) {
			for (int side = 0; side < 4; side++) {
				if (!open[side])
					continue;
				CellBox n = c;
				if (side == 0) n.ix0--;
				if (side == 1) n.ix1++;
				if (side == 2) n.iy0--;
				if (side == 3) n.iy1++;
				bool ok = side < 2 ? strip_clear(side == 0 ? n.ix0 : n.ix1, side == 0 ? n.ix0 : n.ix1, n.iy0, n.iy1)
						   : strip_clear(n.ix0, n.ix1, side == 2 ? n.iy0 : n.iy1, side == 2 ? n.iy0 : n.iy1);
				if (ok)
					c = n;
				else
					open[side] = false;
			}
		}
		c.z0 = -std::numeric_limits<double>::infinity();
		if (flight_)
			for (int iy = c.iy0; iy <= c.iy1; iy++)
				for (int ix = c.ix0; ix <= c.ix1; ix++)
					c.z0 = std::max(c.z0, m_.flight_floor(ix, iy));
		c.z1 = m_.flight_top();
	}

	const std::string &mode_;
	const ClearanceMap &m_;
	bool flight_;
	mutable double zlo_ = 0, zhi_ = 0;
};

// A piece of the path [s0, s1] (arc length) and its box, if it has one.
struct Piece {
	double s0 = 0, s1 = 0;
	P3 a{}, b{};
	bool has_box = false;
	size_t level = 0;
	CellBox box;
};

double length(const P3 &a, const P3 &b, bool flight)
{
	double dz = flight ? b[2] - a[2] : 0;
	return std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + dz * dz);
}

P3 lerp(const P3 &a, const P3 &b, double f)
{
	return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
}

// Covers the path piece a -> b (arc length s0 to s1) with boxes at level
// from on: the whole piece, else its halves (down to a quarter cell), else
// the next level; a piece no level clears gets no box.
void cover(const std::string &mode, const CorridorMaps &maps, size_t level, const P3 &a, const P3 &b, double s0,
	   double s1, int depth, std::vector<Piece> &out)
{
	const TerrainGrid &g = maps.grid();
	auto grid_units = [&](const P3 &p) {
		return P3{(p[0] - g.origin_x_m) / g.resolution_m, (p[1] - g.origin_y_m) / g.resolution_m, p[2]};
	};
	Piece pc;
	pc.s0 = s0;
	pc.s1 = s1;
	pc.a = a;
	pc.b = b;
	pc.level = level;
	if (Grower(mode, *maps.levels()[level]).grow(grid_units(a), grid_units(b), pc.box)) {
		pc.has_box = true;
		out.push_back(pc);
		return;
	}
	constexpr int kMaxDepth = 8;
	if (depth < kMaxDepth && length(a, b, mode == "flight") > 0.25 * g.resolution_m) {
		P3 m = lerp(a, b, 0.5);
		double sm = 0.5 * (s0 + s1);
		cover(mode, maps, level, a, m, s0, sm, depth + 1, out);
		cover(mode, maps, level, m, b, sm, s1, depth + 1, out);
		return;
	}
	if (level + 1 < maps.levels().size()) {
		cover(mode, maps, level + 1, a, b, s0, s1, depth, out);
		return;
	}
	out.push_back(pc);
}

// Consecutive pieces at the same level with the same box become one.
std::vector<Piece> merged(const std::vector<Piece> &pieces)
{
	std::vector<Piece> out;
	for (const Piece &p : pieces) {
		if (!out.empty() && out.back().has_box == p.has_box && out.back().level == p.level &&
		    (!p.has_box || (out.back().box.ix0 == p.box.ix0 && out.back().box.ix1 == p.box.ix1 &&
				    out.back().box.iy0 == p.box.iy0 && out.back().box.iy1 == p.box.iy1 &&
				    out.back().box.z0 == p.box.z0))) {
			out.back().s1 = p.s1;
			out.back().b = p.b;
			continue;
		}
		out.push_back(p);
	}
	return out;
}

std::string piece_text(const Piece &p, bool flight)
{
	char buf[160];
	if (flight)
		std::snprintf(buf, sizeof buf, "(%.3g, %.3g, %.3g) -> (%.3g, %.3g, %.3g)", p.a[0], p.a[1], p.a[2], p.b[0],
			      p.b[1], p.b[2]);
	else
		std::snprintf(buf, sizeof buf, "(%.3g, %.3g) -> (%.3g, %.3g)", p.a[0], p.a[1], p.b[0], p.b[1]);
	return buf;
}

}  // namespace

Corridor build_corridor(const std::string &mode, const std::vector<P3> &path, const CorridorMaps &maps)
{
	if (mode != "ground" && mode != "marine" && mode != "flight")
		throw std::invalid_argument("corridor: mode " + mode + " has no corridor");
	if (path.empty())
		throw std::invalid_argument("corridor: an empty path");
	const bool flight = mode == "flight";
	std::vector<P3> pts = path;
	if (pts.size() == 1)
		pts.push_back(pts[0]);
	std::vector<Piece> pieces;
	double s = 0;
	for (size_t i = 1; i < pts.size(); i++) {
		double d = length(pts[i - 1], pts[i], flight);
		if (d == 0 && pts.size() > 2 && !pieces.empty())
			continue;   // a repeated point adds nothing
		cover(mode, maps, 0, pts[i - 1], pts[i], s, s + d, 0, pieces);
		s += d;
	}
	pieces = merged(pieces);
	const double L = s;
	const TerrainGrid &g = maps.grid();
	Corridor c;
	c.first_box = pieces.front().has_box;
	c.last_box = pieces.back().has_box;
	const double want = maps.levels().front()->clearance();
	for (size_t j = 0; j < pieces.size(); j++) {
		const Piece &p = pieces[j];
		double got = maps.levels()[p.level]->clearance();
		char buf[96];
		if (!p.has_box) {
			c.notes.push_back(piece_text(p, flight) + ": no box, not even the domain's cells hold it");
			continue;
		}
		if (got < want) {
			std::snprintf(buf, sizeof buf, ": cells clear by %.3g m, not %.3g m", got, want);
			c.notes.push_back(piece_text(p, flight) + buf);
		}
		// Overlap with the neighbours (both with boxes) around the shared point.
		auto overlap = [&](size_t k) {
			const Piece &q = pieces[k];
			if (!q.has_box)
				return 0.0;
			return std::min({0.25 * (p.s1 - p.s0), 0.25 * (q.s1 - q.s0), 0.5});
		};
		double s0 = p.s0 - (j > 0 ? overlap(j - 1) : 0), s1 = p.s1 + (j + 1 < pieces.size() ? overlap(j + 1) : 0);
		CorridorBox b;
		b.tau0 = L > 0 ? std::max(0.0, s0 / L) : 0;
		b.tau1 = L > 0 ? std::min(1.0, s1 / L) : 1;
		if (j == 0)
			b.tau0 = 0;
		if (j + 1 == pieces.size())
			b.tau1 = 1;
		b.lo = {g.origin_x_m + p.box.ix0 * g.resolution_m, g.origin_y_m + p.box.iy0 * g.resolution_m};
		b.hi = {g.origin_x_m + (p.box.ix1 + 1) * g.resolution_m, g.origin_y_m + (p.box.iy1 + 1) * g.resolution_m};
		if (flight) {
			b.lo.push_back(p.box.z0);
			b.hi.push_back(p.box.z1);
		}
		c.boxes.push_back(std::move(b));
	}
	return c;
}

}  // namespace hylo::trainer
