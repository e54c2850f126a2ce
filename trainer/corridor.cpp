#include "trainer/corridor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "hylo/clearance.h"
#include "hylo/map.h"
#include "trainer/clearance.hpp"
#include "trainer/modes.hpp"

namespace hylo::trainer {

ClearanceMap::ClearanceMap(const TerrainGrid &g, double r) : m_(onboard_map(g)), r_(r), nx_(g.nx), ny_(g.ny)
{
	hylo_reason why;
	if (hylo_map_inflate(m_.get(), r, &why) != HYLO_OK)
		throw std::invalid_argument(std::string("corridor: ") + why.text);
}

ClearanceMap::~ClearanceMap() = default;

bool ClearanceMap::clear(hylo_mode mode, int ix, int iy) const
{
	return hylo_map_cell_clear(m_.get(), mode, iy * nx_ + ix) != 0;
}

double ClearanceMap::flight_floor(int ix, int iy) const
{
	double f = hylo_map_flight_floor(m_.get(), iy * nx_ + ix);
	return std::isfinite(f) ? f : std::numeric_limits<double>::infinity();
}

double ClearanceMap::flight_top() const
{
	return hylo_map_flight_top(m_.get());
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
	Grower(hylo_mode mode, const ClearanceMap &m) : mode_(mode), m_(m), flight_(mode_desc(mode).air) {}

	// The box of cells around the box with corners a and b (grid units for x
	// and y; a segment's ends), grown while clear; false if the cells around
	// it are not clear. A flight box holds its heights too; lifted, it may
	// start above them (at the highest floor of its cells, below the top).
	bool grow(const P3 &a, const P3 &b, CellBox &box, bool lifted = false)
	{
		const double z0 = std::min(a[2], b[2]);
		if (flight_ && !lifted && std::max(a[2], b[2]) > m_.flight_top() + 1e-9)
			return false;
		for (const auto &xs : axis_seeds(std::min(a[0], b[0]), std::max(a[0], b[0]), m_.nx()))
			for (const auto &ys : axis_seeds(std::min(a[1], b[1]), std::max(a[1], b[1]), m_.ny())) {
				CellBox c{xs.first, xs.second, ys.first, ys.second, 0, 0};
				zlo_ = z0;
				if (lifted && !lift(c))
					continue;
				if (!strip_clear(c.ix0, c.ix1, c.iy0, c.iy1))
					continue;
				expand(c);
				box = c;
				return true;
			}
		return false;
	}

private:
	// A lifted flight box's floor: the highest floor of its seed cells, if
	// they may all be flown over below the top.
	bool lift(const CellBox &c)
	{
		double f = -std::numeric_limits<double>::infinity();
		for (int iy = c.iy0; iy <= c.iy1; iy++)
			for (int ix = c.ix0; ix <= c.ix1; ix++)
				if (ix >= 0 && iy >= 0 && ix < m_.nx() && iy < m_.ny())
					f = std::max(f, m_.flight_floor(ix, iy));
		if (!(f <= m_.flight_top()))
			return false;
		zlo_ = std::max(zlo_, f);
		return true;
	}

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

	const hylo_mode mode_;
	const ClearanceMap &m_;
	bool flight_;
	double zlo_ = 0;   // a flight box's cells must have floors at most this high
};

// A piece of the path [s0, s1] (arc length) and its box, if it has one.
struct Piece {
	double s0 = 0, s1 = 0;
	P3 a{}, b{};
	P3 lo{}, hi{};   // corners of the box round its path
	bool has_box = false, lifted = false;
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

// The fractions of a -> b (grid units) where it crosses a cell edge, inside
// (0, 1), in order.
std::vector<double> cell_crossings(const P3 &a, const P3 &b)
{
	std::vector<double> f;
	for (int k = 0; k < 2; k++) {
		const double d = b[k] - a[k];
		if (d == 0)
			continue;
		for (double u = std::floor(std::min(a[k], b[k])) + 1; u < std::max(a[k], b[k]); u += 1) {
			const double t = (u - a[k]) / d;
			if (t > 1e-9 && t < 1 - 1e-9)
				f.push_back(t);
		}
	}
	std::sort(f.begin(), f.end());
	f.erase(std::unique(f.begin(), f.end(), [](double x, double y) { return y - x < 1e-12; }), f.end());
	return f;
}

// Covers the path piece a -> b (arc length s0 to s1) with boxes at level
// from on: the whole piece, else its halves (down to a quarter cell), else
// on the ground or water its parts between the cell edges it crosses (a
// piece that passes a blocked cell's corner closer than a quarter cell:
// each part lies in one cell; a flight is lifted instead), else the next
// level; a piece no level clears gets no box.
void cover(hylo_mode mode, const CorridorMaps &maps, size_t level, const P3 &a, const P3 &b, double s0,
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
	for (size_t k = 0; k < 3; k++) {
		pc.lo[k] = std::min(a[k], b[k]);
		pc.hi[k] = std::max(a[k], b[k]);
	}
	pc.level = level;
	if (Grower(mode, *maps.levels()[level]).grow(grid_units(a), grid_units(b), pc.box)) {
		pc.has_box = true;
		out.push_back(pc);
		return;
	}
	constexpr int kMaxDepth = 8;
	if (depth < kMaxDepth && length(a, b, mode_desc(mode).air) > 0.25 * g.resolution_m) {
		P3 m = lerp(a, b, 0.5);
		double sm = 0.5 * (s0 + s1);
		cover(mode, maps, level, a, m, s0, sm, depth + 1, out);
		cover(mode, maps, level, m, b, sm, s1, depth + 1, out);
		return;
	}
	const std::vector<double> cuts = mode_desc(mode).air ? std::vector<double>() : cell_crossings(grid_units(a), grid_units(b));
	if (!cuts.empty()) {
		double f0 = 0;
		for (size_t i = 0; i <= cuts.size(); i++) {
			const double f1 = i < cuts.size() ? cuts[i] : 1;
			cover(mode, maps, level, lerp(a, b, f0), lerp(a, b, f1), s0 + f0 * (s1 - s0), s0 + f1 * (s1 - s0),
			      kMaxDepth, out);
			f0 = f1;
		}
		return;
	}
	// A flight the cells around cannot hold at its height: lifted to where
	// they can, at the full clearance (the plan passes too low there).
	if (mode_desc(mode).air && level == 0 && Grower(mode, *maps.levels()[0]).grow(grid_units(a), grid_units(b), pc.box, true)) {
		pc.has_box = pc.lifted = true;
		out.push_back(pc);
		return;
	}
	if (level + 1 < maps.levels().size()) {
		cover(mode, maps, level + 1, a, b, s0, s1, depth, out);
		return;
	}
	out.push_back(pc);
}

// Consecutive boxed pieces at one level (both lifted or neither) whose
// path's box, as a whole, grows clear become one piece: fewer boxes, fewer times the
// trajectory must be in the next box by a given time. Consecutive pieces
// without a box become one too.
std::vector<Piece> joined(const std::vector<Piece> &pieces, hylo_mode mode, const CorridorMaps &maps)
{
	const TerrainGrid &g = maps.grid();
	auto grid_units = [&](const P3 &p) {
		return P3{(p[0] - g.origin_x_m) / g.resolution_m, (p[1] - g.origin_y_m) / g.resolution_m, p[2]};
	};
	std::vector<Piece> out;
	for (const Piece &p : pieces) {
		if (!out.empty()) {
			Piece &q = out.back();
			P3 lo, hi;
			for (size_t k = 0; k < 3; k++) {
				lo[k] = std::min(q.lo[k], p.lo[k]);
				hi[k] = std::max(q.hi[k], p.hi[k]);
			}
			CellBox box = q.box;
			bool boxless = !q.has_box && !p.has_box;
			if (boxless || (q.has_box && p.has_box && q.lifted == p.lifted && q.level == p.level &&
					Grower(mode, *maps.levels()[p.level]).grow(grid_units(lo), grid_units(hi), box, p.lifted))) {
				q.s1 = p.s1;
				q.b = p.b;
				q.lo = lo;
				q.hi = hi;
				q.box = box;
				continue;
			}
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

namespace {

// A polyline by arc length.
struct Polyline {
	std::vector<P3> pts;
	std::vector<double> at;   // arc length at each point
	P3 point(double s) const
	{
		size_t i = 1;
		while (i + 1 < pts.size() && at[i] < s)
			i++;
		double d = at[i] - at[i - 1];
		return lerp(pts[i - 1], pts[i], d > 0 ? std::min(1.0, std::max(0.0, (s - at[i - 1]) / d)) : 0);
	}
};

CorridorBox metric_box(const Piece &p, const TerrainGrid &g, bool flight)
{
	CorridorBox b;
	b.lo = {g.origin_x_m + p.box.ix0 * g.resolution_m, g.origin_y_m + p.box.iy0 * g.resolution_m};
	b.hi = {g.origin_x_m + (p.box.ix1 + 1) * g.resolution_m, g.origin_y_m + (p.box.iy1 + 1) * g.resolution_m};
	if (flight) {
		b.lo.push_back(p.box.z0);
		b.hi.push_back(p.box.z1);
	}
	return b;
}

bool holds(const CorridorBox &b, const P3 &x)
{
	for (size_t k = 0; k < b.lo.size(); k++)
		if (x[k] < b.lo[k] - 1e-9 || x[k] > b.hi[k] + 1e-9)
			return false;
	return true;
}

// Where the corridor hands over from box a (piece pa) to box b (the next
// piece pb): the middle of the stretch of path round their shared point
// that both boxes hold (searched from 60% of pa to 40% of pb, so that
// hand-overs stay in order), and the half-width of the time both bound
// the knots: half that stretch, at least 5 cm, at most 0.5 m and a tenth
// of the shorter piece.
std::pair<double, double> hand_over(const Polyline &path, const Piece &pa, const CorridorBox &a, const Piece &pb,
				    const CorridorBox &b)
{
	const double h = 0.05, la = pa.s1 - pa.s0, lb = pb.s1 - pb.s0;
	auto both = [&](double s) {
		P3 x = path.point(s);
		return holds(a, x) && holds(b, x);
	};
	double u0 = pa.s1, u1 = pa.s1;
	while (u0 - h >= pa.s0 + 0.6 * la && both(u0 - h))
		u0 -= h;
	while (u1 + h <= pb.s0 + 0.4 * lb && both(u1 + h))
		u1 += h;
	double w = std::min({0.5, 0.1 * std::min(la, lb), std::max(0.5 * (u1 - u0), 0.05)});
	return {0.5 * (u0 + u1), w};
}

}  // namespace

Corridor build_corridor(hylo_mode mode, const std::vector<P3> &path, const CorridorMaps &maps)
{
	const hylo_mode_desc &d = mode_desc(mode);
	if (!d.planar && !d.air)   // a phase plane is not on the map
		throw std::invalid_argument(std::string("corridor: mode ") + d.name + " has no corridor");
	if (path.empty())
		throw std::invalid_argument("corridor: an empty path");
	const bool flight = d.air;
	Polyline line;
	line.pts = path;
	if (line.pts.size() == 1)
		line.pts.push_back(line.pts[0]);
	line.at.assign(line.pts.size(), 0.0);
	std::vector<Piece> pieces;
	for (size_t i = 1; i < line.pts.size(); i++) {
		double d = length(line.pts[i - 1], line.pts[i], flight);
		line.at[i] = line.at[i - 1] + d;
		if (d == 0 && line.pts.size() > 2 && !pieces.empty())
			continue;   // a repeated point adds nothing
		cover(mode, maps, 0, line.pts[i - 1], line.pts[i], line.at[i - 1], line.at[i], 0, pieces);
	}
	pieces = joined(pieces, mode, maps);
	const double L = line.at.back();
	Corridor c;
	c.first_box = pieces.front().has_box;
	c.last_box = pieces.back().has_box;
	const double want = maps.levels().front()->clearance();
	std::vector<CorridorBox> boxes;
	for (const Piece &p : pieces) {
		boxes.push_back(p.has_box ? metric_box(p, maps.grid(), flight) : CorridorBox{});
		char buf[96];
		if (!p.has_box) {
			c.notes.push_back(piece_text(p, flight) + ": no box, not even the domain's cells hold it");
			continue;
		}
		if (p.lifted) {
			std::snprintf(buf, sizeof buf, ": passes below the clear floor, lifted to z >= %.3g m", p.box.z0);
			c.notes.push_back(piece_text(p, flight) + buf);
		}
		if (maps.levels()[p.level]->clearance() < want) {
			std::snprintf(buf, sizeof buf, ": cells clear by %.3g m, not %.3g m",
				      maps.levels()[p.level]->clearance(), want);
			c.notes.push_back(piece_text(p, flight) + buf);
		}
	}
	// Each box bounds the knots from the hand-over from the previous box to
	// the hand-over to the next (its piece's own ends next to a piece
	// without a box), by arc length.
	std::vector<double> start(pieces.size()), end(pieces.size());
	for (size_t j = 0; j < pieces.size(); j++) {
		start[j] = pieces[j].s0;
		end[j] = pieces[j].s1;
	}
	for (size_t j = 0; j + 1 < pieces.size(); j++)
		if (pieces[j].has_box && pieces[j + 1].has_box) {
			auto [at, w] = hand_over(line, pieces[j], boxes[j], pieces[j + 1], boxes[j + 1]);
			end[j] = at + w;
			start[j + 1] = at - w;
		}
	for (size_t j = 0; j < pieces.size(); j++) {
		if (!pieces[j].has_box)
			continue;
		CorridorBox &b = boxes[j];
		b.tau0 = j == 0 || L <= 0 ? 0 : std::max(0.0, start[j] / L);
		b.tau1 = j + 1 == pieces.size() || L <= 0 ? 1 : std::min(1.0, end[j] / L);
		c.boxes.push_back(std::move(b));
	}
	return c;
}

}  // namespace hylo::trainer
