// Safe corridors (trainer/corridor.hpp, docs/smoothing.md "Clearance"):
// corridor boxes as knot bounds of a collocation phase, through mesh
// refinement (the bounds of a finer mesh); a phase cut into pieces at its
// boxes' hand-overs and joined back; the builder's boxes on a staircase shore; and two smoothed
// plans checked point by point against the hazards of docs/smoothing.md,
// written out here from that definition (not the corridor's cell test):
//   (a) Ambot driving to a staircase shoreline and paddling on: with
//       corridors every knot and midpoint is in its mode's domain and keeps
//       the margin; without them (the smoother before corridors) the same
//       check fails, so it can;
//   (b) Drivocopter hopping over a wall under a low ceiling, margin 0.25 m:
//       every flight knot and midpoint keeps body + margin from the
//       terrain's columns (the wall gates alone keep 0.18 m), and the
//       free hand-overs between boxes let the first solve reach the cost
//       that rebuilding the corridors crept towards.
// Prints TAP.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "tests/tap.hpp"
#include "tests/trainer/grids.hpp"
#include "trainer/collocation.hpp"
#include "trainer/corridor.hpp"
#include "trainer/hand_overs.hpp"
#include "trainer/mode_config.hpp"
#include "trainer/hs_phase.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"
#include "trainer/smoother.hpp"
#include "trainer/switching.hpp"

namespace {

using namespace hylo::trainer;

std::string fmt(double v)
{
	return tap_num(v, 4);
}

// ---- the hazards of docs/smoothing.md, point by point ----------------------

double gap(double a0, double a1, double b0, double b1)
{
	return std::max({0.0, b0 - a1, a0 - b1});
}

// Distance from (x, y) to the rectangle [x0, x1] x [y0, y1].
double to_rect(double x, double y, double x0, double x1, double y0, double y1)
{
	return std::hypot(gap(x, x, x0, x1), gap(y, y, y0, y1));
}

struct PointCheck {
	bool inside = true;       // in the mode's domain
	double clearance = 0;     // distance to the nearest hazard less the body
};

// A ground or marine position: in a cell of its class (closed squares), and
// its distance to obstacles, wall edges (ground: adjacent ground cells
// stepping more than max_step) and the map's edge.
PointCheck planar_check(const TerrainGrid &m, hylo_mode mode, double x, double y, double body)
{
	const double res = m.resolution_m, X1 = m.origin_x_m + m.nx * res, Y1 = m.origin_y_m + m.ny * res;
	const int8_t own = mode == HYLO_MODE_GROUND ? 1 : 2;
	PointCheck c;
	double d = std::min({x - m.origin_x_m, X1 - x, y - m.origin_y_m, Y1 - y});
	c.inside = false;
	for (int iy = 0; iy < m.ny; iy++)
		for (int ix = 0; ix < m.nx; ix++) {
			size_t k = static_cast<size_t>(iy * m.nx + ix);
			double x0 = m.origin_x_m + ix * res, y0 = m.origin_y_m + iy * res;
			if (m.terrain[k] == own && to_rect(x, y, x0, x0 + res, y0, y0 + res) == 0)
				c.inside = true;
			if (m.terrain[k] == 0)
				d = std::min(d, to_rect(x, y, x0, x0 + res, y0, y0 + res));
			if (mode != HYLO_MODE_GROUND || m.terrain[k] != 1)
				continue;
			auto wall = [&](size_t j) {
				return m.terrain[j] == 1 && std::fabs(m.height_m[j] - m.height_m[k]) > m.max_step_m;
			};
			if (ix + 1 < m.nx && wall(k + 1))
				d = std::min(d, to_rect(x, y, x0 + res, x0 + res, y0, y0 + res));
			if (iy + 1 < m.ny && wall(k + static_cast<size_t>(m.nx)))
				d = std::min(d, to_rect(x, y, x0, x0 + res, y0 + res, y0 + res));
		}
	c.clearance = d - body;
	return c;
}

// A flight position: at least 0.5 m above every cell it is over, and its
// distance to the terrain's columns, the map's edge and the ceiling.
PointCheck flight_check(const TerrainGrid &m, double x, double y, double z, double body)
{
	const double res = m.resolution_m, X1 = m.origin_x_m + m.nx * res, Y1 = m.origin_y_m + m.ny * res;
	PointCheck c;
	double d = std::min({x - m.origin_x_m, X1 - x, y - m.origin_y_m, Y1 - y, m.ceiling_m - z});
	for (int iy = 0; iy < m.ny; iy++)
		for (int ix = 0; ix < m.nx; ix++) {
			double h = m.height_m[static_cast<size_t>(iy * m.nx + ix)];
			double x0 = m.origin_x_m + ix * res, y0 = m.origin_y_m + iy * res;
			double flat = to_rect(x, y, x0, x0 + res, y0, y0 + res);
			if (flat == 0 && z < h + kAirClearanceM)
				c.inside = false;
			d = std::min(d, std::hypot(flat, std::max(0.0, z - h)));
		}
	c.clearance = d - body;
	return c;
}

// The worst knot or midpoint of a smoothed trajectory: outside its domain
// first, then the least clearance. "" when every point keeps margin.
std::string worst_point(const MultiPhaseSolution &s, const TerrainGrid &m, double body, double margin,
			double *least = nullptr)
{
	std::string worst;
	double low = std::numeric_limits<double>::infinity();
	for (size_t k = 0; k < s.phases.size(); k++) {
		const Trajectory &tr = s.phases[k].traj;
		for (size_t i = 0; i < tr.t.size(); i++) {
			const double *x = &tr.x[i * static_cast<size_t>(tr.nx)];
			PointCheck c = s.modes[k] == HYLO_MODE_FLIGHT ? flight_check(m, x[0], x[1], x[2], body)
							      : planar_check(m, s.modes[k], x[0], x[1], body);
			std::string where = "phase " + std::to_string(k) + " (" + hylo_mode_str(s.modes[k]) + ") point " + std::to_string(i) +
					    " at (" + fmt(x[0]) + ", " + fmt(x[1]) +
					    (s.modes[k] == HYLO_MODE_FLIGHT ? ", " + fmt(x[2]) : "") + ")";
			if (!c.inside)
				return where + " is outside its domain";
			if (c.clearance < low) {
				low = c.clearance;
				if (c.clearance < margin - 1e-9)
					worst = where + " keeps " + fmt(c.clearance) + " m < margin " + fmt(margin) + " m";
			}
		}
	}
	if (least)
		*least = low;
	return worst;
}

// ---- corridors in one collocation phase --------------------------------------

const std::vector<CorridorBox> kL = {CorridorBox{0, 0.55, {0, 0}, {1, 5}}, CorridorBox{0.45, 1, {0, 4}, {5, 5}}};

// Where a point at normalized time tau may be by the L's boxes: the
// intersection of those whose interval holds tau ({lo x, lo y, hi x, hi y}).
std::array<double, 4> l_room(double tau)
{
	std::array<double, 4> r{-1e300, -1e300, 1e300, 1e300};
	for (const CorridorBox &b : kL)
		if (tau >= b.tau0 - 1e-12 && tau <= b.tau1 + 1e-12)
			r = {std::max(r[0], b.lo[0]), std::max(r[1], b.lo[1]), std::min(r[2], b.hi[0]), std::min(r[3], b.hi[1])};
	return r;
}

// The variable bounds a ground phase of n segments with the L's corridor
// gives its knots and midpoints (the mesh refinement builds the finer
// phase the same way, from the same setup): each point's position bounded
// by the boxes of its time, the ends pinned where the corridor holds them.
void l_bounds(const RobotParams &ambot)
{
	bool ok = true;
	std::string why;
	for (int n : {5, 10, 20}) {
		internal::PhaseSetup s;
		s.segments = n;
		auto b = state_bounds(HYLO_MODE_GROUND, ambot);
		double a[4] = {0.5, 0.5, 0, 1.5708}, e[4] = {4.5, 4.5, 0, 0};
		s.first_lo = s.first_hi = full_state(HYLO_MODE_GROUND, ambot, a);
		s.last_lo = s.last_hi = full_state(HYLO_MODE_GROUND, ambot, e);
		s.guess = {s.first_lo, s.last_lo};
		s.corridor = kL;
		internal::HsPhase<GroundModel> ph(GroundModel(ambot.mode("ground"), ambot.g), s);
		std::vector<double> xl(static_cast<size_t>(ph.nvar())), xu(xl.size()), gl(static_cast<size_t>(ph.ncon())),
			gu(gl.size());
		ph.bounds(xl.data(), xu.data(), gl.data(), gu.data());
		const int nz = GroundModel::NX + GroundModel::NU;
		for (int p = 0; p <= 2 * n && ok; p++) {
			double tau = p <= n ? static_cast<double>(p) / n : (p - n - 1 + 0.5) / n;
			std::array<double, 4> r = l_room(tau);
			if (p == 0 || p == n)   // pinned ends inside the corridor
				r = {p ? 4.5 : 0.5, p ? 4.5 : 0.5, p ? 4.5 : 0.5, p ? 4.5 : 0.5};
			const double *lo = &xl[static_cast<size_t>(p * nz)], *hi = &xu[static_cast<size_t>(p * nz)];
			if (lo[0] != r[0] || lo[1] != r[1] || hi[0] != r[2] || hi[1] != r[3] ||
			    (p != 0 && p != n && lo[2] != b.first[2])) {
				ok = false;
				why = std::to_string(n) + " segments, point " + std::to_string(p) + " (tau " + fmt(tau) + "): [" +
				      fmt(lo[0]) + ", " + fmt(hi[0]) + "] x [" + fmt(lo[1]) + ", " + fmt(hi[1]) + "]";
			}
		}
	}
	check(ok, "a phase's corridor bounds every knot and midpoint by the boxes of its time, on meshes of 5, 10 "
		  "and 20 segments", why);
}

// Ambot drives (0.5, 0.5) -> (4.5, 4.5) through the L: up the column
// x in [0, 1], then along the row y in [4, 5]; every knot and midpoint of
// the solution lies in a box (the boxes' windows time the guess; where the
// way hands over from one to the other is free, trainer/hand_overs.hpp).
void l_shaped_phase(const RobotParams &ambot)
{
	double a[4] = {0.5, 0.5, 0, 1.5708}, c[4] = {0.5, 4.5, 0, 0}, b[4] = {4.5, 4.5, 0, 0};
	PhaseSpec s = phase_between(HYLO_MODE_GROUND, ambot, a, b, a, b, 12);
	s.guess = {full_state(HYLO_MODE_GROUND, ambot, a), full_state(HYLO_MODE_GROUND, ambot, c), full_state(HYLO_MODE_GROUND, ambot, b)};
	s.corridor = kL;
	MultiPhaseProblem p;
	p.phases = {s};
	SolveOptions o;
	o.replay_state_tol = 0.05;   // the smoother's: a sharp turn
	MultiPhaseSolution m = solve_multiphase(ambot, p, o);
	bool in = m.converged;
	std::string why = in ? "" : "not converged (" + m.status_text + ", " + m.rejection + ")";
	if (in) {
		const Trajectory &tr = m.phases[0].traj;
		for (size_t i = 0; i < tr.t.size() && in; i++) {
			double x = tr.x[i * 6], y = tr.x[i * 6 + 1];
			bool held = false;
			for (const CorridorBox &b : kL)
				held = held || (x >= b.lo[0] - 1e-7 && x <= b.hi[0] + 1e-7 && y >= b.lo[1] - 1e-7 &&
						y <= b.hi[1] + 1e-7);
			if (!held) {
				in = false;
				why = "point " + std::to_string(i) + ": (" + fmt(x) + ", " + fmt(y) + ") outside the boxes";
			}
		}
	}
	std::printf("# L-shaped corridor: %.6g J, %d segments, %.2f s\n", m.cost,
		    m.phases.empty() ? 0 : m.phases[0].segments, m.solve_seconds);
	check(in, "an L-shaped corridor: the solution's knots and midpoints keep to its boxes (the hand-over between "
		  "them free)", why);
	PhaseSpec bad = s;
	bad.corridor[1].lo = {2, 4};
	bad.corridor[1].hi = {5, 5};
	p.phases = {bad};
	check_throws([&] { solve_multiphase(ambot, p, SolveOptions()); }, "overlap in time but not in space",
		     "boxes that overlap in time but not in space are refused");
}

// A ground phase of 20 segments through three boxes whose windows overlap
// ([0, 0.4], [0.3, 0.7], [0.6, 1]): three pieces, cut in the middle of each
// overlap (0.35, 0.65), each with its box re-timed to its own time, its
// share of the segments and of the duration guess, its slice of the guess
// at its times, the mode's bounds and the inset at its inner ends; a fixed
// duration, or boxes with a stretch between them, is not cut, nor a piece
// shorter than four segments. And the
// pieces' solutions joined back: one knot at each hand-over, durations,
// costs and segments summed, the replay failed if one piece's did.
void hand_over_pieces_split(const RobotParams &ambot)
{
	const internal::ModeInfo info = internal::mode_info(HYLO_MODE_GROUND, ambot);
	double a[4] = {0, 0, 0, 0}, m[4] = {3, 0, 0, 0}, b[4] = {10, 0, 0, 0};
	internal::PhaseSetup s;
	s.segments = 20;
	s.T_guess = 10;
	s.guess = {full_state(HYLO_MODE_GROUND, ambot, a), full_state(HYLO_MODE_GROUND, ambot, m),
		   full_state(HYLO_MODE_GROUND, ambot, b)};
	s.guess_at = {0, 0.3, 1};
	s.first_lo = s.first_hi = s.guess[0];
	s.last_lo = s.last_hi = s.guess[2];
	s.corridor = {CorridorBox{0, 0.4, {-1, -1}, {4.5, 1}}, CorridorBox{0.3, 0.7, {2.5, -1}, {7.5, 1}},
		      CorridorBox{0.6, 1, {5.5, -1}, {11, 1}}};
	const std::vector<internal::PhaseSetup> p = internal::hand_over_pieces(s, info);
	std::string why;
	auto expect = [&](bool ok, const std::string &what) {
		if (!ok && why.empty())
			why = what;
	};
	expect(p.size() == 3, std::to_string(p.size()) + " pieces");
	if (p.size() == 3) {
		const double share[3] = {0.35, 0.3, 0.35};
		for (size_t k = 0; k < 3; k++) {
			const std::string n = "piece " + std::to_string(k) + ": ";
			expect(p[k].corridor.size() == 1 && p[k].corridor[0].lo[0] == s.corridor[k].lo[0] &&
				       p[k].corridor[0].tau0 == 0 && p[k].corridor[0].tau1 == 1,
			       n + "its box");
			expect(std::fabs(p[k].T_guess - 10 * share[k]) < 1e-12 && std::fabs(p[k].mesh_share - share[k]) < 1e-12,
			       n + "T guess " + fmt(p[k].T_guess) + ", mesh share " + fmt(p[k].mesh_share));
			expect(p[k].segments == static_cast<int>(std::lround(20 * share[k])), n + std::to_string(p[k].segments) + " segments");
			expect(p[k].inset_first == (k > 0) && p[k].inset_last == (k < 2), n + "insets");
			expect(k == 0 ? p[k].first_lo == s.first_lo : p[k].first_lo == info.bounds.x_lo, n + "first bounds");
			expect(k == 2 ? p[k].last_hi == s.last_hi : p[k].last_hi == info.bounds.x_hi, n + "last bounds");
			expect(p[k].guess.size() == p[k].guess_at.size() && p[k].guess_at.front() == 0 && p[k].guess_at.back() == 1,
			       n + "guess times");
		}
		// Piece 0: the start, the middle state at 0.3 / 0.35 of it, then x at
		// 0.35 of the phase (3 + 0.05 / 0.7 * 7 = 3.5).
		expect(p[0].guess.size() == 3 && std::fabs(p[0].guess_at[1] - 0.3 / 0.35) < 1e-12 &&
			       std::fabs(p[0].guess[2][0] - 3.5) < 1e-12,
		       "piece 0's guess slice");
		expect(p[1].guess.size() == 2 && std::fabs(p[1].guess[0][0] - 3.5) < 1e-12 && std::fabs(p[1].guess[1][0] - 6.5) < 1e-12,
		       "piece 1's guess slice");
	}
	internal::PhaseSetup fixed = s;
	fixed.T_fixed = 10;
	expect(internal::hand_over_pieces(fixed, info).size() == 1, "a fixed duration was cut");
	internal::PhaseSetup apart = s;
	apart.corridor[1].tau0 = 0.45;
	apart.corridor[2].tau0 = 0.75;
	expect(internal::hand_over_pieces(apart, info).size() == 1, "boxes with a stretch between them were cut");
	// A piece shorter than four of the phase's segments (here 2) stays in
	// its neighbour's: box 1 over 0.35..0.45 goes with box 2.
	internal::PhaseSetup short_box = s;
	short_box.corridor[1].tau1 = 0.5;
	short_box.corridor[2].tau0 = 0.4;
	const std::vector<internal::PhaseSetup> merged = internal::hand_over_pieces(short_box, info);
	expect(merged.size() == 2 && merged[0].corridor.size() == 1 && merged[1].corridor.size() == 2 &&
		       std::fabs(merged[1].T_guess - 6.5) < 1e-12,
	       "a piece of 2 segments was not merged into its neighbour's: " + std::to_string(merged.size()) + " pieces");

	MultiPhaseSolution m3;
	for (int k = 0; k < 3; k++) {
		Solution ph;
		ph.T = 1 + k;
		ph.cost = 10;
		ph.segments = 2;
		ph.replayed = ph.replay_ok = k != 1;
		ph.replay_error = 0.1 * k;
		ph.traj.nx = 1;
		ph.traj.nu = 1;
		ph.traj.t = {0, 0.5 * ph.T, ph.T};
		ph.traj.x = {10.0 * k, 10.0 * k + 5, 10.0 * k + 10};
		ph.traj.u = {0, 0, 0};
		m3.phases.push_back(ph);
		m3.modes.push_back(HYLO_MODE_GROUND);
	}
	const MultiPhaseSolution j = internal::joined_pieces(m3, {0, 0, 0});
	const bool one = j.phases.size() == 1 && j.modes.size() == 1;
	expect(one, std::to_string(j.phases.size()) + " phases joined");
	if (one) {
		const Solution &ph = j.phases[0];
		expect(ph.traj.t == std::vector<double>{0, 0.5, 1, 2, 3, 4.5, 6} &&
			       ph.traj.x == std::vector<double>{0, 5, 10, 15, 20, 25, 30},
		       "joined trajectory");
		expect(ph.T == 6 && ph.cost == 30 && ph.segments == 6 && !ph.replay_ok && ph.replay_error == 0.2,
		       "joined sums and replay");
	}
	check(why.empty(), "hand-overs: a phase through three overlapping boxes is three pieces with their shares "
			   "(a short one merged), joined back into one", why);
}

// ---- the builder and the smoother -------------------------------------------

// 16 x 16 cells of 1 m: ground where ix + iy < 16 (a staircase shore along
// the diagonal), water beyond; an obstacle at cells (3..4, 8..9).
TerrainGrid staircase()
{
	TerrainGrid m = flat_ground(16, 16);
	for (int iy = 0; iy < 16; iy++)
		for (int ix = 0; ix < 16; ix++)
			m.terrain[static_cast<size_t>(iy * 16 + ix)] = ix + iy < 16 ? 1 : 2;
	for (int iy = 8; iy < 10; iy++)
		for (int ix = 3; ix < 5; ix++)
			m.terrain[static_cast<size_t>(iy * 16 + ix)] = 0;
	return m;
}

Waypoint wp(const std::string &mode, double x, double y, double z_or_v, double theta, bool guard)
{
	Waypoint w;
	w.mode = parse_mode(mode);
	w.guard = guard;
	w.state[0] = x;
	w.state[1] = y;
	w.state[2] = z_or_v;
	w.state[3] = theta;
	return w;
}

// Ambot from (2, 2) on land to the shore point (8, 8.5) (the edge between
// ground cell (7, 8) and water cell (8, 8)), then paddling to (13, 13).
std::vector<Waypoint> shore_plan()
{
	return {wp("ground", 2, 2, 0, 0.785, false), wp("ground", 5, 5.5, 0.5, 0.785, false),
		wp("ground", 8, 8.5, 0.5, 0.785, true), wp("marine", 8, 8.5, 0.5, 0.785, true),
		wp("marine", 13, 13, 0, 0.785, false)};
}

void staircase_corridor(const RobotParams &ambot)
{
	TerrainGrid m = staircase();
	const double r = ambot.body_radius_m + 0.1;
	CorridorMaps maps(m, r, 0.02);
	Corridor g = build_corridor(HYLO_MODE_GROUND, {{2, 2, 0}, {5, 5.5, 0}, {8, 8.5, 0}}, maps);
	Corridor w = build_corridor(HYLO_MODE_MARINE, {{8, 8.5, 0}, {13, 13, 0}}, maps);
	const ClearanceMap &clear = *maps.levels().front();
	bool ok = g.notes.empty() && w.notes.empty() && g.first_box && g.last_box && w.first_box && !g.boxes.empty();
	std::string why = ok ? "" : "notes: " + (g.notes.empty() ? std::string() : g.notes[0]) +
					(w.notes.empty() ? std::string() : w.notes[0]);
	for (const Corridor *c : {&g, &w})
		for (const CorridorBox &b : c->boxes)
			for (int iy = static_cast<int>(b.lo[1]); ok && iy < static_cast<int>(b.hi[1]); iy++)
				for (int ix = static_cast<int>(b.lo[0]); ok && ix < static_cast<int>(b.hi[0]); ix++)
					if (!clear.clear(c == &g ? HYLO_MODE_GROUND : HYLO_MODE_MARINE, ix, iy)) {
						ok = false;
						why = "cell (" + std::to_string(ix) + ", " + std::to_string(iy) + ") of a box is not clear";
					}
	check(ok, "staircase: every box is made of cells clear by body + margin + pad", why);
	// Every point of the plan's path is in a box whose interval holds its
	// arc-length time; consecutive intervals overlap.
	ok = g.boxes.size() >= 2;
	for (size_t j = 1; ok && j < g.boxes.size(); j++)
		ok = g.boxes[j].tau0 < g.boxes[j - 1].tau1 && g.boxes[j].tau0 > g.boxes[j - 1].tau0;
	ok = ok && g.boxes.front().tau0 == 0 && g.boxes.back().tau1 == 1;
	check(ok, "staircase: the ground corridor's intervals cover [0, 1], each overlapping the next",
	      std::to_string(g.boxes.size()) + " boxes");
	// The ground corridor ends on the shore edge x = 8 and the water one
	// starts there: their boxes meet on the edge, not over a cell.
	const CorridorBox &gl = g.boxes.back(), &wf = w.boxes.front();
	ok = gl.hi[0] == 8 && wf.lo[0] == 8 && std::max(gl.lo[1], wf.lo[1]) <= 8.5 && std::min(gl.hi[1], wf.hi[1]) >= 8.5;
	check(ok, "staircase: the last ground box and the first water box meet on the shore edge x = 8",
	      "ground x <= " + fmt(gl.hi[0]) + ", water x >= " + fmt(wf.lo[0]));
}

// A path that passes a blocked cell's corner 1.7 cm away through clear
// cells only (a generated scene's plan did, and its corridor fell back to
// the domain there): 0.5 m cells, a rock over cells (27..32, 13), so at
// body + margin + pad (0.47 m) cell (26, 12), touching the rock's corner
// (13.5, 6.5), is blocked; the plan's edge passes its corner (13, 6) at
// (13, 5.983). Its corridor has full-clearance boxes only (quarter-cell
// halves still straddle the corner: the parts between cell edges do not).
void corner_pass(const RobotParams &ambot)
{
	TerrainGrid m = flat_ground(60, 48, 0.5);
	for (int ix = 27; ix <= 32; ix++)
		m.terrain[static_cast<size_t>(13 * 60 + ix)] = 0;
	CorridorMaps maps(m, ambot.body_radius_m + 0.1, 0.02);
	Corridor g = build_corridor(HYLO_MODE_GROUND, {{11.8912, 7.2921, 0}, {13.3401, 5.5821, 0}, {16.5834, 3.2932, 0}}, maps);
	const ClearanceMap &clear = *maps.levels().front();
	bool ok = g.notes.empty() && g.first_box && g.last_box && !g.boxes.empty();
	std::string why = g.notes.empty() ? "" : g.notes[0];
	for (const CorridorBox &b : g.boxes)
		for (long iy = std::lround(b.lo[1] / 0.5); ok && iy < std::lround(b.hi[1] / 0.5); iy++)
			for (long ix = std::lround(b.lo[0] / 0.5); ok && ix < std::lround(b.hi[0] / 0.5); ix++)
				if (!clear.clear(HYLO_MODE_GROUND, static_cast<int>(ix), static_cast<int>(iy))) {
					ok = false;
					why = "cell (" + std::to_string(ix) + ", " + std::to_string(iy) + ") of a box is not clear";
				}
	check(ok, "a path passing a blocked cell's corner by 1.7 cm: boxes of full clearance, no note", why);
}

// A clearance the map cannot give (3 m on a 16 m map with a rock) is not
// dropped silently: the corridor says which pieces got less.
void too_wide()
{
	TerrainGrid m = staircase();
	CorridorMaps maps(m, 3.0, 0.02);
	Corridor g = build_corridor(HYLO_MODE_GROUND, {{2, 2, 0}, {5, 5.5, 0}, {8, 8.5, 0}}, maps);
	bool said = !g.notes.empty() && g.notes[0].find("not 3.02 m") != std::string::npos;
	check(said && g.boxes.size() >= 1, "a clearance the map cannot give: the corridor's notes say where it gives less",
	      g.notes.empty() ? "no note" : g.notes[0]);
}

// (a): the plan smoothed with corridors keeps every knot and midpoint in
// its domain with the margin; without them it does not.
void staircase_smoothing(const RobotParams &ambot)
{
	TerrainGrid m = staircase();
	SmoothOptions on, off;
	off.corridors = false;
	MultiPhaseSolution a = smooth_plan(ambot, shore_plan(), m, {}, on);
	MultiPhaseSolution b = smooth_plan(ambot, shore_plan(), m, {}, off);
	double la = 0, lb = 0;
	std::string wa = a.converged ? worst_point(a, m, ambot.body_radius_m, on.margin_m, &la) : "not converged";
	std::string wb = b.converged ? worst_point(b, m, ambot.body_radius_m, on.margin_m, &lb) : "not converged";
	std::printf("# staircase: with corridors %.6g J, %.2f s, least clearance %.3f m; without %.6g J, %.2f s: %s\n",
		    a.cost, a.solve_seconds, la, b.cost, b.solve_seconds, wb.c_str());
	for (const std::string &n : a.notes)
		std::printf("# note: %s\n", n.c_str());
	check(a.converged && wa.empty() && a.notes.empty(),
	      "staircase shore: with corridors every knot and midpoint is in its domain, clear by the margin", wa);
	check(b.converged && !wb.empty(),
	      "staircase shore: without corridors the same check finds a point that is not (so it can fail)",
	      b.converged ? "every point passed" : "not converged");
}

// (b): a 9 x 5 m map of 1 m cells, floor at height 0, a wall 2 m high over
// x in [4, 5], ceiling 4 m: the gate over the wall is 1.5 m tall (2.5 m to
// the ceiling). Drivocopter takes off at (1.5, 2.5) and lands at (7.5, 2.5),
// with a margin of 0.25 m: the wall gates alone (without corridors) let the
// flight cross 0.5 m above the wall's top edges, a clearance of 0.18 m.
void chasm_gate(const RobotParams &drivo)
{
	TerrainGrid m = flat_ground(9, 5);
	m.ceiling_m = 4;
	for (int iy = 0; iy < 5; iy++)
		m.height_m[static_cast<size_t>(iy * 9 + 4)] = 2;
	std::vector<Waypoint> hop = {wp("ground", 1.5, 2.5, 0, 0, true), wp("flight", 1.5, 2.5, 1, 0, true),
				     wp("flight", 7.5, 2.5, 1, 0, true), wp("ground", 7.5, 2.5, 0, 0, true)};
	hop[1].state[3] = hop[2].state[3] = 0;
	SmoothOptions on;
	on.margin_m = 0.25;
	MultiPhaseSolution a = smooth_plan(drivo, hop, m, TakeoffLanding{100, 40}, on);
	double least = 0;
	std::string w = a.converged ? worst_point(a, m, drivo.body_radius_m, on.margin_m, &least) : "not converged: " + a.status_text + " " + a.rejection;
	std::printf("# chasm gate: %.6g J, %.2f s, least clearance %.3f m\n", a.cost, a.solve_seconds, least);
	for (const std::string &n : a.notes)
		std::printf("# note: %s\n", n.c_str());
	check(a.converged && w.empty(), "chasm with a 1.5 m gate, margin 0.25 m: every flight knot and midpoint keeps "
					"body + margin from the terrain's columns, the map's edge and the ceiling", w);
	// With each hand-over between boxes at a fixed time, the corridors
	// built along the plan's path held the flights back and rounds of
	// rebuilding crept towards the optimum, to 1,322.0 J (docs/decisions.md,
	// "Table I at 70 m"). With free hand-overs the first solve is there, and
	// a rebuild has little left to save.
	double first = a.cost;
	for (const std::string &n : a.notes)
		if (std::sscanf(n.c_str(), "flight corridors rebuilt along the solution: %lf", &first) == 1)
			break;
	check(a.converged && a.cost < 1310 && first < 1.005 * a.cost,
	      "chasm gate: free hand-overs between boxes: below 1,310 J from the corridors along the plan's path, "
	      "a rebuild saving under 0.5%",
	      "along the plan's path " + fmt(first) + " J, smoothed " + fmt(a.cost) + " J");
}

}  // namespace

int main(int argc, char **argv)
{
	if (!pin_numerics(argc, argv))
		return 1;
	RobotParams ambot = load_robot("trainer/params/ambot.yaml");
	RobotParams drivo = load_robot("trainer/params/drivocopter.yaml");
	l_bounds(ambot);
	l_shaped_phase(ambot);
	staircase_corridor(ambot);
	too_wide();
	corner_pass(ambot);
	hand_over_pieces_split(ambot);
	staircase_smoothing(ambot);
	chasm_gate(drivo);
	return tap_finish();
}
