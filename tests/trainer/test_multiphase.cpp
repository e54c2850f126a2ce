// Multi-phase collocation (trainer/collocation.hpp, switching.hpp): Ipopt's
// derivative checker on a joined ground -> marine problem, the hybrid double
// integrator's two-phase optimum against a dense sweep of the switching
// velocity on the guard p = 0 (the paper's reference, Fig. 10), and an Ambot
// shore crossing whose free switch point does at least as well as a fixed one,
// the takeoff and landing conditions of a drive-fly-drive chain, and the
// smoother's wall gates and takeoff-at-the-start plans (problem structure).
// Prints TAP.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "tests/tap.hpp"
#include "tests/trainer/grids.hpp"
#include "trainer/clearance.hpp"
#include "trainer/collocation.hpp"
#include "trainer/fallbacks.hpp"
#include "trainer/numerics.hpp"
#include "trainer/params.hpp"
#include "trainer/replay.hpp"
#include "trainer/smooth_alternatives.hpp"
#include "trainer/smoother.hpp"
#include "trainer/switching.hpp"

namespace {

using namespace hylo::trainer;
std::string fmt(double v)
{
	return tap_num(v, 9);
}

void di_case(const RobotParams &di, double a0, double a1, double b0, double b1)
{
	double a[2] = {a0, a1}, b[2] = {b0, b1};
	auto [sweep, v_sweep] = di_swept_optimum(di, a, b);
	MultiPhaseSolution m = di_two_phase(di, a, b, 0.0);
	std::string name = "double integrator (" + fmt(a0) + ", " + fmt(a1) + ") -> (" + fmt(b0) + ", " + fmt(b1) + ")";
	std::printf("# %s: two-phase %.9g (switch v %.6f), swept %.9g (v %.6f)\n", name.c_str(), m.cost,
		    m.converged ? m.phases[1].traj.x[1] : NAN, sweep, v_sweep);
	check(m.converged && m.cost <= sweep * (1 + 1e-6) && m.cost >= sweep * (1 - 5e-3),
	      name + ": two-phase optimum within 0.5% of the swept one and not above it",
	      fmt(m.cost) + " vs " + fmt(sweep));
	bool joined = m.converged && std::fabs(m.phases[0].traj.x[m.phases[0].traj.x.size() - 2]) < 1e-7 &&
		      std::fabs(m.phases[1].traj.x[0]) < 1e-7 &&
		      std::fabs(m.phases[0].traj.x.back() - m.phases[1].traj.x[1]) < 1e-7;
	check(joined, name + ": the phases meet on the guard p = 0 with one velocity");
	check(m.converged && m.replay_error < 1e-6 && std::fabs(m.replay_cost - m.cost) < 1e-5 * m.cost,
	      name + ": both phases replay", fmt(m.replay_error));
}

// Ipopt's first- and second-order derivative checker on problem; names the
// first entry it flags.
void derivative_test(const RobotParams &robot, const MultiPhaseProblem &p, double perturbation,
		     const std::string &name)
{
	SolveOptions o;
	o.derivative_test_perturbation = perturbation;
	char path[] = "/tmp/hylo-dtest-XXXXXX";
	int fd = mkstemp(path);
	close(fd);
	o.derivative_test_file = path;
	solve_multiphase(robot, p, o);
	std::ifstream f(path);
	std::ostringstream log;
	log << f.rdbuf();
	unlink(path);
	std::string first;
	size_t star = log.str().find("\n*");
	if (star != std::string::npos)
		first = log.str().substr(star + 1, log.str().find('\n', star + 1) - star - 1);
	check(log.str().find("No errors detected by derivative checker") != std::string::npos,
	      "Ipopt derivative checker (first and second order): " + name, first);
}

void derivative_tests(const RobotParams &ambot)
{
	// Short phases (as in the single-phase checks): the objective's curvature
	// in the inputs grows with T and swamps the finite differences.
	double a[4] = {0.1, 0.2, 0.3, 0.4}, s[4] = {0.4, 0.5, 0.6, 0.45}, b[4] = {0.7, 0.8, 0.9, 0.5};
	MultiPhaseProblem p;
	p.phases = {phase_between(HYLO_MODE_GROUND, ambot, a, nullptr, a, s, 3),
		    phase_between(HYLO_MODE_MARINE, ambot, nullptr, b, s, b, 3)};
	join_phases(p, 0, ambot, SwitchGuard{0.4, -1.0, 0.4, 2.0, 0});
	derivative_test(ambot, p, 1e-8, "ambot ground -> marine, joined");

}

// Drive, take off, fly, land, drive: the switch conditions of docs/models.md section 6.
void takeoff_landing_joins(const RobotParams &drivo)
{
	double g0[4] = {0, 0, 0, 0}, g1[4] = {5, 0, 0, 0}, g3[4] = {20, 0, 0, 0};
	double f1[6] = {5, 0, 7, 0, 0, 0}, f2[6] = {15, 0, 7, 0, 0, 0};
	MultiPhaseProblem q;
	q.phases = {phase_between(HYLO_MODE_GROUND, drivo, g0, nullptr, g0, g1, 3),
		    phase_between(HYLO_MODE_FLIGHT, drivo, nullptr, nullptr, f1, f2, 3),
		    phase_between(HYLO_MODE_GROUND, drivo, nullptr, g3, g1, g3, 3)};
	join_phases(q, 0, drivo, SwitchGuard{2, 0, 8, 0, 6}, TakeoffLanding{100, 40});
	join_phases(q, 1, drivo, SwitchGuard{12, 0, 18, 0, 6}, TakeoffLanding{100, 40});
	double hover_xs[6] = {0, 0, 7, 0, 0, 0};
	std::vector<double> hover = full_state(HYLO_MODE_FLIGHT, drivo, hover_xs);
	bool ok = q.switch_cost == 140;
	const PhaseSpec &d1 = q.phases[0], &fl = q.phases[1], &d2 = q.phases[2];
	for (int i : {2, 3, 5})   // at rest before takeoff and after landing
		ok = ok && d1.last_lo[i] == 0 && d1.last_hi[i] == 0 && d2.first_lo[i] == 0 && d2.first_hi[i] == 0;
	ok = ok && d2.first_lo[4] == 0 && d2.first_hi[4] == 0;   // heading 0 (the hover's yaw)
	for (int i = 2; i < 16; i++)   // hover 1 m above the 6 m platform, yaw 0, rotors at phi_n
		ok = ok && fl.first_lo[i] == hover[i] && fl.first_hi[i] == hover[i] && fl.last_lo[i] == hover[i] &&
		     fl.last_hi[i] == hover[i];
	ok = ok && fl.first_lo[0] < -1e10 && fl.last_hi[1] > 1e10;   // position free, tied by rows
	// Rows per switch: px and py carried, and two for the guard segment.
	ok = ok && q.rows.size() == 8;
	check(ok, "Drivocopter takeoff and landing: rest on the ground, hover at h + 1, position carried, "
		  "switching costs added");
}


void shore_crossing(const RobotParams &ambot)
{
	// Land x < 4, water beyond; start on land at rest, goal in the water at rest.
	double a[4] = {0, 0, 0, 0}, b[4] = {8, 3, 0, 0};
	double th = std::atan2(3.0, 8.0), s[4] = {4, 1.5, 0.4, th};
	MultiPhaseProblem p;
	p.phases = {phase_between(HYLO_MODE_GROUND, ambot, a, nullptr, a, s, 20),
		    phase_between(HYLO_MODE_MARINE, ambot, nullptr, b, s, b, 20)};
	join_phases(p, 0, ambot, SwitchGuard{4, -4, 4, 6, 0});
	MultiPhaseSolution m = solve_multiphase(ambot, p, SolveOptions());
	Solution g = solve_bvp(HYLO_MODE_GROUND, ambot, a, s, SolveOptions());
	Solution w = solve_bvp(HYLO_MODE_MARINE, ambot, s, b, SolveOptions());
	double fixed = g.cost + w.cost;
	std::printf("# ambot shore crossing: free switch %.6g J (T %.3g s, %.2f s to solve), "
		    "fixed switch %.6g J\n", m.cost, m.T, m.solve_seconds, fixed);
	check(m.converged && g.converged && w.converged && m.cost <= fixed * (1 + 1e-6),
	      "Ambot ground -> marine: a free switch point costs no more than a fixed one",
	      fmt(m.cost) + " vs " + fmt(fixed));
	const auto &gx = m.phases[0].traj.x, &mx = m.phases[1].traj.x;
	size_t end = gx.size() - 6;   // the ground phase's last state
	bool on_shore = m.converged && std::fabs(gx[end] - 4) < 1e-6 && gx[end + 1] >= -4 - 1e-6 &&
			gx[end + 1] <= 6 + 1e-6;
	bool carried = m.converged;
	for (int i = 0; carried && i < 6; i++)
		carried = std::fabs(mx[static_cast<size_t>(i)] - gx[end + static_cast<size_t>(i)]) < 1e-6;
	double phin = full_state(HYLO_MODE_MARINE, ambot, s)[6] / s[2] * gx[end + 2];
	carried = carried && std::fabs(mx[6] - phin) < 1e-6 && std::fabs(mx[7] - phin) < 1e-6;
	check(on_shore && carried, "Ambot ground -> marine: the switch is on the shoreline and the reset "
				  "carries the state (phi = phi_n(vx))");
	check(m.converged && m.replay_error < kReplayStateTol, "Ambot ground -> marine: both phases replay",
	      fmt(m.replay_error));
}

void bad_problems(const RobotParams &di)
{
	double a[2] = {0.5, 0}, b[2] = {-0.5, 0};
	MultiPhaseProblem p;
	p.phases = {phase_between(HYLO_MODE_DI_POS, di, a, nullptr, a, a, 5),
		    phase_between(HYLO_MODE_DI_POS, di, nullptr, b, a, a, 5)};
	check_throws([&] { join_phases(p, 0, di, SwitchGuard{}); }, "di_pos -> di_pos",
		     "a switch between two phases of one mode is refused");
	MultiPhaseProblem q;
	q.phases = {phase_between(HYLO_MODE_DI_POS, di, a, nullptr, a, a, 5)};
	LinearRow r;
	r.terms = {{KnotRef{3, true, 0}, 1.0}};
	q.rows = {r};
	check_throws([&] { solve_multiphase(di, q, SolveOptions()); }, "phase 3", "a row naming a missing phase is refused");
}
// A 20 x 4 m map, 1 m cells: a 6 m platform for x < 8, the floor (height 0)
// beyond. A flight from the platform down to the floor crosses the wall at
// x = 8: the smoother cuts it there into two phases meeting at least 6.5 m high.
void wall_gates(const RobotParams &drivo)
{
	TerrainGrid m = flat_ground(20, 4);
	for (int iy = 0; iy < 4; iy++)
		for (int ix = 0; ix < 8; ix++)
			m.height_m[static_cast<size_t>(iy * 20 + ix)] = 6;
	auto wp = [](hylo_mode mode, double x, double z, bool guard) {
		Waypoint w;
		w.mode = mode;
		w.guard = guard;
		w.state[0] = x;
		w.state[1] = 2;
		if (mode == HYLO_MODE_FLIGHT)
			w.state[2] = z;
		return w;
	};
	const hylo_mode G = HYLO_MODE_GROUND, F = HYLO_MODE_FLIGHT;
	std::vector<Waypoint> plan = {wp(G, 2, 0, false), wp(G, 6, 0, true),  wp(F, 6, 7, true),
				      wp(F, 12, 1, true), wp(G, 12, 0, true), wp(G, 16, 0, false)};
	MultiPhaseProblem p = smoothing_problem(drivo, plan, m, TakeoffLanding{100, 40});
	bool ok = p.phases.size() == 4 && p.phases[1].mode == HYLO_MODE_FLIGHT && p.phases[2].mode == HYLO_MODE_FLIGHT;
	if (ok) {
		const PhaseSpec &a = p.phases[1];
		ok = a.last_lo[0] == 8 && a.last_hi[0] == 8 && a.last_lo[2] == 6.5 && a.guess.back()[2] >= 6.5;
	}
	check(ok, "a flight over a wall is cut at the wall: the two phases meet on x = 8, at least 6.5 m high");
	check(p.switch_cost == 140, "the cut adds no cost; takeoff and landing do (" + fmt(p.switch_cost) + ")");
	// Takeoff and landing points slide over an area of level ground (cell
	// centres, within 6 m per axis), not along a line: the platform x < 8 for
	// the takeoff at (6, 2), the floor from x = 8 for the landing at (12, 2).
	SmoothOptions plain;
	plain.corridors = false;
	MultiPhaseProblem pp = smoothing_problem(drivo, plan, m, TakeoffLanding{100, 40}, plain);
	ok = pp.phases.size() == 4;
	if (ok) {
		const PhaseSpec &d = pp.phases[0], &f = pp.phases[2];
		ok = d.last_lo[0] == 0.5 && d.last_hi[0] == 7.5 && d.last_lo[1] == 0.5 && d.last_hi[1] == 3.5 &&
		     f.last_lo[0] == 8.5 && f.last_hi[0] == 18.5 && f.last_lo[1] == 0.5 && f.last_hi[1] == 3.5;
	}
	check(ok, "takeoff and landing areas: x in [0.5, 7.5] on the platform, [8.5, 18.5] on the floor, y in [0.5, 3.5]");
	// With corridors (the default), only the cells that keep the body
	// (0.32 m) plus margin and pad (0.12 m) from the map's edge and the wall:
	// not the outer rows and columns, nor the two columns at the wall.
	ok = p.phases.size() == 4;
	if (ok) {
		const PhaseSpec &d = p.phases[0], &f = p.phases[2];
		ok = d.last_lo[0] == 1.5 && d.last_hi[0] == 6.5 && d.last_lo[1] == 1.5 && d.last_hi[1] == 2.5 &&
		     f.last_lo[0] == 9.5 && f.last_hi[0] == 18.5 && f.last_lo[1] == 1.5 && f.last_hi[1] == 2.5;
	}
	check(ok, "clear takeoff and landing areas: x in [1.5, 6.5] on the platform, [9.5, 18.5] on the floor, "
		  "y in [1.5, 2.5]");
	// Taking off at the first waypoint and landing at the last: no ground
	// phases, the flight starts and ends hovering 1 m above those points.
	std::vector<Waypoint> hop = {wp(G, 2, 0, true), wp(F, 2, 7, true), wp(F, 12, 1, true), wp(G, 12, 0, true)};
	MultiPhaseProblem q = smoothing_problem(drivo, hop, m, TakeoffLanding{100, 40});
	ok = q.phases.size() == 2 && q.phases[0].mode == HYLO_MODE_FLIGHT && q.phases[1].mode == HYLO_MODE_FLIGHT &&
	     q.switch_cost == 140;
	if (ok)
		ok = q.phases[0].first_lo[0] == 2 && q.phases[0].first_hi[2] == 7 && q.phases[0].first_lo[5] == 0 &&
		     q.phases[1].last_hi[0] == 12 && q.phases[1].last_lo[2] == 1;
	check(ok, "a plan that takes off at its start and lands at its goal is flight only, hover to hover");
	// Straightened: a sideways S-curve on the ground is laid on the line
	// between its ends (evenly, heading along it); the flight run's inner
	// point moves onto its line too; ends, guards, speeds and modes stay.
	std::vector<Waypoint> s = {wp(G, 2, 0, false), wp(G, 4, 0, false), wp(G, 6, 0, true),
				   wp(F, 6, 7, true), wp(F, 9, 2, false), wp(F, 12, 1, true), wp(G, 12, 0, true)};
	s[1].state[1] = 3.5;   // off the line y = 2
	s[1].state[2] = 2;
	s[4].state[3] = 8;
	std::vector<Waypoint> st = straightened(s);
	ok = st.size() == s.size() && st[1].state[0] == 4 && st[1].state[1] == 2 && st[1].state[2] == 2 &&
	     st[1].state[3] == 0 && st[4].state[0] == 9 && st[4].state[2] == 4 && st[4].state[3] == 8;
	for (size_t i = 0; i < s.size(); i++)
		ok = ok && st[i].mode == s[i].mode && st[i].guard == s[i].guard &&
		     (i == 1 || i == 4 || std::equal(s[i].state, s[i].state + 6, st[i].state));
	check(ok, "straightened: inner waypoints on the line between each run's ends, the rest kept");
}

// smooth_alternatives on the double integrator from (0.8, 0.2) to (-0.8, 0):
// a path that crosses p = 0 three times, given first (as if the graph had
// ranked it first), and the direct one crossing once. The smoothed direct
// path is cheaper and is chosen; a count budget of 1 smooths the first alone.
void alternatives_choice(const RobotParams &di)
{
	const hylo_mode N = HYLO_MODE_DI_NEG, P = HYLO_MODE_DI_POS;
	auto w = [](hylo_mode mode, double p, double v, bool guard) {
		Waypoint x;
		x.mode = mode;
		x.state[0] = p;
		x.state[1] = v;
		x.guard = guard;
		return x;
	};
	PlanAlternative thrice{0, 2.0, {w(P, 0.8, 0.2, false), w(P, 0.4, -0.6, false), w(P, 0, -0.6, true),
					  w(N, 0, -0.6, true), w(N, -0.2, 0, false), w(N, 0, 0.6, true),
					  w(P, 0, 0.6, true), w(P, 0.2, 0, false), w(P, 0, -0.6, true),
					  w(N, 0, -0.6, true), w(N, -0.8, 0, false)}};
	PlanAlternative once{1, 2.5, {w(P, 0.8, 0.2, false), w(P, 0.4, -0.6, false), w(P, 0, -0.8, true),
				       w(N, 0, -0.8, true), w(N, -0.4, -0.6, false), w(N, -0.8, 0, false)}};
	TerrainGrid plane = flat_ground(40, 40, 0.05);   // scenes/di.yaml: the phase plane [-1, 1]^2, all "ground"
	plane.origin_x_m = plane.origin_y_m = -1;
	AlternativesChoice c = smooth_alternatives(di, {thrice, once}, plane, {}, {}, {});
	bool ok = c.outcomes.size() == 2 && c.outcomes[0].smoothed && c.outcomes[1].smoothed &&
		  c.outcomes[0].result.ok && c.outcomes[1].result.ok;
	std::string costs = ok ? fmt(c.outcomes[0].result.solution.cost) + " (three crossings) vs " +
					 fmt(c.outcomes[1].result.solution.cost) + " (one)"
			       : "not both smoothed";
	std::printf("# alternatives: %s\n", costs.c_str());
	for (const AlternativeOutcome &o : c.outcomes)
		for (const std::string &r : o.result.rejections)
			std::printf("# rejected %s\n", r.c_str());
	check(ok && c.chosen == 1 && c.outcomes[1].result.solution.cost < c.outcomes[0].result.solution.cost,
	      "alternatives: the cheapest smoothed is chosen, not the first given", costs);
	AlternativesBudget one;
	one.max_count = 1;
	c = smooth_alternatives(di, {thrice, once}, plane, {}, {}, one);
	check(c.outcomes.size() == 2 && c.outcomes[0].smoothed && !c.outcomes[1].smoothed && c.chosen == 0 &&
		      c.outcomes[1].skipped.find("count budget") != std::string::npos,
	      "alternatives: a count budget of 1 smooths the first alone and says why not the rest",
	      c.outcomes.size() == 2 ? c.outcomes[1].skipped : "");
}

// The choice prefers a safe trajectory to a cheaper unsafe one, and takes
// the cheapest unsafe one only when none is safe.
void alternatives_prefer_safe()
{
	auto outcome = [](bool ok, double cost, bool safe) {
		AlternativeOutcome o;
		o.smoothed = true;
		o.result.ok = ok;
		o.result.solution.cost = cost;
		o.clearance.safe = safe;
		return o;
	};
	check(choose_alternative({outcome(true, 10, false), outcome(true, 12, true), outcome(false, 5, true)}) == 1,
	      "alternatives: a safe trajectory wins over a cheaper one the exact check rejects");
	check(choose_alternative({outcome(true, 12, false), outcome(true, 10, false)}) == 1,
	      "alternatives: none safe: the cheapest (published not safe)");
	check(choose_alternative({outcome(false, 1, true), outcome(true, 3, true), outcome(true, 3, true)}) == 1,
	      "alternatives: a failed smoothing is never chosen; equal costs: the earlier");
	check(choose_alternative({outcome(false, 1, true)}) == -1, "alternatives: none ok: none chosen");
}

}  // namespace

// Ground round a corner to the shore x = 4, then water to the goal: the
// ground's corridor is an L of two boxes (up x <= 1, then along
// 2 <= y <= 3), so the way round rides the corner's faces. With
// corridor_inset_m every point but the phase ends keeps 0.01 m inside its
// boxes; the switch point stays on the shore (an inset there would leave
// the two phases no common point).
void corridor_inset(const RobotParams &ambot)
{
	double a[4] = {0, 0, 0, M_PI / 2}, b[4] = {8, 2.5, 0, 0}, s[4] = {4, 2.5, 0.4, 0};
	MultiPhaseProblem p;
	p.phases = {phase_between(HYLO_MODE_GROUND, ambot, a, nullptr, a, s, 20),
		    phase_between(HYLO_MODE_MARINE, ambot, nullptr, b, s, b, 20)};
	join_phases(p, 0, ambot, SwitchGuard{4, -4, 4, 6, 0});
	p.phases[0].corridor = {{0, 0.5, {-1, -1}, {1, 3}}, {0.5, 1, {0, 2}, {4, 3}}};
	p.phases[1].corridor = {{0, 1, {4, -4}, {9, 6}}};
	// The least depth of a phase-interior point in its boxes: how far inside
	// the box that holds it deepest (the hand-over between boxes is free, so
	// which box holds a point is not fixed by its time).
	auto nearest_face = [&](const MultiPhaseSolution &m) {
		double d = INFINITY;
		for (size_t k = 0; k < 2 && m.converged; k++) {
			const Trajectory &tr = m.phases[k].traj;
			const size_t nx = static_cast<size_t>(tr.nx), n = tr.t.size();
			for (size_t i = 1; i + 1 < n; i++) {
				double depth = -INFINITY;
				for (const CorridorBox &box : p.phases[k].corridor) {
					double in = INFINITY;
					for (size_t c = 0; c < 2; c++)
						in = std::min({in, tr.x[i * nx + c] - box.lo[c], box.hi[c] - tr.x[i * nx + c]});
					depth = std::max(depth, in);
				}
				d = std::min(d, depth);
			}
		}
		return d;
	};
	MultiPhaseSolution on_face = solve_multiphase(ambot, p, SolveOptions());
	for (PhaseSpec &ps : p.phases)
		ps.corridor_inset_m = 0.01;
	MultiPhaseSolution m = solve_multiphase(ambot, p, SolveOptions());
	const auto &gx = m.converged ? m.phases[0].traj.x : std::vector<double>{};
	const bool on_shore = m.converged && std::fabs(gx[gx.size() - 6] - 4) < 1e-6;
	check(on_face.converged && nearest_face(on_face) < 1e-3 && on_shore && nearest_face(m) >= 0.01 - 1e-9,
	      "corridor inset: a phase that rides its boxes' faces keeps 0.01 m inside, the switch on the shore",
	      "without " + fmt(nearest_face(on_face)) + " m, with " + fmt(nearest_face(m)) + " m");
}

// The graph path fallback keeps its corridors: Ambot's plan along y = 0.5
// on a 2 m wide strip (the map's edge a hazard: 0.15 m beyond the body at
// the waypoints), headings -0.8 rad at the waypoints. Each edge solved on
// its own swings towards the edge, 0.09 m beyond the body; each edge in
// its corridor keeps the 0.1 m margin.
void graph_path_corridors(const RobotParams &ambot)
{
	TerrainGrid m = flat_ground(12, 4, 0.5);
	auto wp = [](double x, double v) {
		Waypoint w;
		w.mode = HYLO_MODE_GROUND;
		w.state[0] = x;
		w.state[1] = 0.5;
		w.state[2] = v;
		w.state[3] = -0.8;
		return w;
	};
	const std::vector<Waypoint> plan = {wp(1, 0), wp(2.5, 0), wp(4, 0)};
	SmoothOptions free_edges;
	free_edges.corridors = false;
	MultiPhaseSolution a = graph_path_trajectory(ambot, plan, m, TakeoffLanding{}, free_edges);
	MultiPhaseSolution b = graph_path_trajectory(ambot, plan, m, TakeoffLanding{}, SmoothOptions());
	ClearanceCheck ca = check_clearance(a, m, ambot.body_radius_m, 0.1), cb = check_clearance(b, m, ambot.body_radius_m, 0.1);
	check(a.converged && b.converged && b.phases.size() == 2 && !ca.safe && cb.safe,
	      "graph path: each edge in its corridor keeps the margin (on its own it does not)",
	      ca.text() + " / " + cb.text());
}

// Headings continue across the wrap at +-pi as the planner priced them: a
// quarter turn left from 3pi/4 to -3pi/4 (written 2 pi below) and a half
// turn written as 3.141593 (just above pi, which the wrap makes a right
// turn) towards a goal on the left are guessed, and end, turning left.
void headings_unwound(const RobotParams &ambot)
{
	TerrainGrid m = flat_ground(12, 8, 0.5);
	auto wp = [](double x, double y, double v, double theta) {
		Waypoint w;
		w.mode = HYLO_MODE_GROUND;
		w.state[0] = x, w.state[1] = y, w.state[2] = v, w.state[3] = theta;
		return w;
	};
	const double kTheta = 4;   // the full state's heading
	const std::vector<Waypoint> quarter = {wp(2, 2, 0, 2.356194), wp(3, 3, 0.5, 3.141593), wp(3, 5, 0, -2.356194)};
	const PhaseSpec q = smoothing_problem(ambot, quarter, m, TakeoffLanding{}).phases.at(0);
	check(std::fabs(q.guess.at(2)[kTheta] - (-2.356194 + 2 * M_PI)) < 1e-6 && q.last_lo.at(kTheta) == q.guess.at(2)[kTheta] &&
		      q.last_hi.at(kTheta) == q.last_lo.at(kTheta),
	      "smoothing: headings continue across +-pi (the last one 2 pi above the plan's)",
	      fmt(q.guess.at(2)[kTheta]) + ", end " + fmt(q.last_lo.at(kTheta)));
	const std::vector<Waypoint> half = {wp(2, 2, 0, 0), wp(2, 4, 0, 3.141593)};
	const PhaseSpec h = smoothing_problem(ambot, half, m, TakeoffLanding{}).phases.at(0);
	check(std::fabs(h.last_lo.at(kTheta) - M_PI) < 1e-6, "smoothing: a half turn turns towards the goal's side",
	      fmt(h.last_lo.at(kTheta)));
}

int main(int argc, char **argv)
{
	if (!pin_numerics(argc, argv))
		return 1;
	RobotParams di = load_robot("trainer/params/di.yaml");
	RobotParams ambot = load_robot("trainer/params/ambot.yaml");
	RobotParams drivo = load_robot("trainer/params/drivocopter.yaml");
	derivative_tests(ambot);
	takeoff_landing_joins(drivo);
	wall_gates(drivo);
	di_case(di, 0.8, 0.2, -0.8, 0.0);
	di_case(di, 0.7, -0.1, -0.5, 0.2);
	shore_crossing(ambot);
	corridor_inset(ambot);
	graph_path_corridors(ambot);
	headings_unwound(ambot);
	bad_problems(di);
	alternatives_choice(di);
	alternatives_prefer_safe();
	return tap_finish();
}
