// Case study 3's chasms (tools/casestudies/chasm.cpp): the walls found in the
// committed scenes, a chasm widened from a narrower one equal to the
// committed wider scene (the crossover solves on widths in between), and the
// fixed sequences' plans: their mode sequence, ends at rest on the start and
// goal, switch points at the walls (a cell from them, or the body and margin
// and a cell), and every waypoint as before the profile of any number of
// chasms (a fingerprint of the plans). Two chasms made from the 30 m one
// (--two-chasms): its walls, its 8 routes, each route's plan driving on the
// segments it names and flying above every wall top between.
// Prints TAP.
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/tap.hpp"
#include "tools/casestudies/chasm.hpp"

using namespace hylo::casestudies;
using hylo::trainer::Waypoint;

namespace {

// FNV-1a (64 bits) of every waypoint of the six fixed sequences on the
// scene, switch points placed at 0 and half way, in hex floats.
unsigned long long plans_fingerprint(const Profile &c)
{
	unsigned long long h = 1469598103934665603ull;
	for (const char *seq : {"F", "DF", "DFD", "FDF", "DFDF", "DFDFD"})
		for (double lambda : {0.0, 0.5}) {
			std::string text = seq;
			for (const Waypoint &w : sequence_plan(c, seq, lambda)) {
				char b[64];
				std::snprintf(b, sizeof b, " %d %d", w.mode, static_cast<int>(w.guard));
				text += b;
				for (double v : w.state) {
					std::snprintf(b, sizeof b, " %a", v);
					text += b;
				}
			}
			for (unsigned char ch : text)
				h = (h ^ ch) * 1099511628211ull;
		}
	return h;
}

// Where a flight's guess passes within 0.5 m of a wall lower than 0.94 m
// above its top (the flight clearance 0.5 m plus the 0.44 m), on the
// straight lines between its waypoints too (the corridors are built along
// them); "" if nowhere.
std::string low_at_edges(const Profile &c, const std::vector<Waypoint> &p, const std::string &what)
{
	std::string low;
	for (size_t i = 1; i < p.size(); i++) {
		if (p[i].mode != HYLO_MODE_FLIGHT || p[i - 1].mode != HYLO_MODE_FLIGHT)
			continue;
		for (int k = 0; k <= 20; k++) {
			const double x = p[i - 1].state[0] + (p[i].state[0] - p[i - 1].state[0]) * k / 20;
			const double z = p[i - 1].state[2] + (p[i].state[2] - p[i - 1].state[2]) * k / 20;
			bool near = false;
			for (size_t j = 0; j < c.walls.size(); j++)
				near = near || (std::fabs(x - c.walls[j]) < 0.5 &&
						z < std::max(c.heights[j], c.heights[j + 1]) + 0.94);
			if (near) {
				low += what + " at (" + std::to_string(x) + ", " + std::to_string(z) + ") ";
				break;
			}
		}
	}
	return low;
}

bool same_cells(const hylo::scene::Scene &a, const hylo::scene::Scene &b)
{
	return a.nx == b.nx && a.ny == b.ny && a.terrain == b.terrain && a.height_m == b.height_m &&
	       a.goal.goal.x == b.goal.goal.x && a.goal.start.x == b.goal.start.x;
}

// What is wrong with route r's plan on the profile ("" if nothing): its
// modes, rest at start and goal, ground legs on the route's segments (each
// waypoint at least a margin from the walls), flights forward, 1 m above the
// surface and 1 m above every wall top they pass (0.94 m near each wall's
// edge, on the lines between waypoints too), and switch points a margin from
// a wall when placed at 0.
std::string route_fault(const Profile &c, const Route &r, double lambda)
{
	const std::vector<Waypoint> p = sequence_plan(c, r, lambda);
	const hylo_mode G = HYLO_MODE_GROUND;
	std::string want = "DF";   // a takeoff at the start is a ground waypoint too
	for (size_t k = 0; k < r.landings.size(); k++)
		want += "DF";
	want += "D";
	if (letters(p) != want)
		return "modes " + letters(p) + ", not " + want;
	if (p.front().mode != G || p.front().state[0] != c.x_start || p.front().state[2] != 0 || p.back().mode != G ||
	    p.back().state[0] != c.x_goal || p.back().state[2] != 0)
		return "does not start and end at rest on the start and goal";
	std::vector<size_t> legs;   // the segment of each ground run
	size_t i = 0;
	while (i < p.size()) {
		size_t j = i;
		while (j + 1 < p.size() && p[j + 1].mode == p[i].mode)
			j++;
		const double x0 = p[i].state[0], x1 = p[j].state[0];
		if (p[i].mode == G) {
			const size_t s = c.segment_at(x0);
			legs.push_back(s);
			for (size_t k = i; k <= j; k++) {
				const double x = p[k].state[0];
				if (c.segment_at(x) != s || (s > 0 && x < c.lo(s) + c.margin - 1e-12) ||
				    (s < c.last() && x > c.hi(s) - c.margin + 1e-12) || p[k].state[1] != c.y)
					return "ground waypoint at " + std::to_string(x) + " off its segment or within a margin of a wall";
			}
		} else {
			const size_t s0 = c.segment_at(x0), s1 = c.segment_at(x1);
			double top = 0;
			for (size_t s = s0; s <= s1; s++)
				top = std::max(top, c.heights[s]);
			for (size_t k = i; k <= j; k++) {
				const double x = p[k].state[0], z = p[k].state[2];
				if (k > i && x < p[k - 1].state[0])
					return "a flight goes backwards at " + std::to_string(x);
				if (z < c.heights[c.segment_at(x)] + 1 || (x > x0 && x < x1 && z < top + 1))
					return "flight waypoint at x " + std::to_string(x) + " only " + std::to_string(z) + " m high";
			}
		}
		i = j + 1;
	}
	std::vector<size_t> want_legs;
	if (r.drive_start)
		want_legs.push_back(0);
	want_legs.insert(want_legs.end(), r.landings.begin(), r.landings.end());
	if (r.drive_goal)
		want_legs.push_back(c.last());
	if (!r.drive_start && !legs.empty() && legs.front() == 0)   // the takeoff point, not a drive
		legs.erase(legs.begin());
	if (!r.drive_goal && !legs.empty() && legs.back() == c.last())
		legs.pop_back();
	if (legs != want_legs)
		return "drives on other segments than the route's";
	if (std::string low = low_at_edges(c, p, "flight"); !low.empty())
		return low;
	if (lambda == 0)
		for (size_t k = 1; k + 1 < p.size(); k++)
			if (p[k].guard && p[k].mode == G) {
				bool at_wall = false;
				for (double w : c.walls)
					at_wall = at_wall || std::fabs(std::fabs(p[k].state[0] - w) - c.margin) < 1e-12;
				if (!at_wall)
					return "switch point at " + std::to_string(p[k].state[0]) + " not a margin from a wall";
			}
	if (!(route_of_plan(c, p) == r))
		return "route_of_plan reads it as " + route_name(c, route_of_plan(c, p));
	return "";
}

bool throws(const Profile &c, const std::string &name)
{
	try {
		route_of(c, name);
	} catch (const std::invalid_argument &) {
		return true;
	}
	return false;
}

}  // namespace

int main()
{
	const hylo::scene::Scene s30 = hylo::scene::load("scenes/chasm_030.yaml");
	const hylo::scene::Scene s50 = hylo::scene::load("scenes/chasm_050.yaml");
	const hylo::scene::Scene s70 = hylo::scene::load("scenes/chasm_070.yaml");
	const Profile c50 = profile_of(s50, 0);
	check(c50.walls == std::vector<double>{20, 70} && c50.heights == std::vector<double>{6, 0, 6} &&
		      c50.x_start == 10 && c50.x_goal == 80 && c50.segment_at(19.9) == 0 && c50.segment_at(20) == 1 &&
		      c50.segment_at(70) == 2,
	      "chasm_050: walls at 20 and 70 m, platforms 6 m over the floor, start and goal 10 m back",
	      "walls " + std::to_string(c50.walls.size()));

	const hylo::scene::Scene w = widened(s50, c50, 20);
	check(same_cells(w, s70) && w.name == "chasm_070", "chasm_050 widened by 20 m is chasm_070, cell for cell");
	const Profile c51 = profile_of(widened(s50, c50, 1), 0);
	check(c51.walls == std::vector<double>{20, 71} && c51.x_goal == 81,
	      "widened by 1 m: the far wall and the goal move 1 m");
	const Profile c30 = profile_of(s30, 0);
	check(same_cells(chasms(s30, c30, {50}), s50) && same_cells(chasms(s50, c50, {30}), s30) &&
		      chasms(s50, c50, {30}).name == "chasm_030",
	      "chasms() with one length: chasm_030 made 50 m wide is chasm_050, chasm_050 made 30 m wide chasm_030");

	// The single-chasm plans, waypoint for waypoint as before the profile of
	// any number of chasms (fingerprints of the two-wall code's plans, with
	// switch points a cell from the walls and with the Drivocopter's 0.44 m).
	check(plans_fingerprint(c30) == 0x168ef995a6b3766dull && plans_fingerprint(c50) == 0x20773ac611ab2074ull &&
		      plans_fingerprint(profile_of(s30, 0.44)) == 0x73b4f22348296721ull &&
		      plans_fingerprint(profile_of(s50, 0.44)) == 0x8238ba1e47db57d8ull,
	      "the fixed sequences' plans on chasm_030 and chasm_050 are the ones of before, waypoint for waypoint");

	bool all = true;
	std::string why;
	for (const std::string seq : {"F", "DF", "DFD", "FDF", "DFDF", "DFDFD"}) {
		std::vector<Waypoint> p = sequence_plan(c50, seq, 0.0);
		const Waypoint &a = p.front(), &b = p.back();
		bool ok = letters(p) == (seq.front() == 'F' ? "D" : "") + seq + (seq.back() == 'F' ? "D" : "");
		ok = ok && a.mode == HYLO_MODE_GROUND && a.state[0] == 10 && a.state[2] == 0;
		ok = ok && b.mode == HYLO_MODE_GROUND && b.state[0] == 80 && b.state[2] == 0;
		// Switch points (ground guards) between the ends: one per change of
		// mode in seq, each a cell from a wall.
		size_t at_walls = 0;
		for (size_t i = 1; i + 1 < p.size(); i++)
			if (p[i].guard && p[i].mode == HYLO_MODE_GROUND) {
				double x = p[i].state[0];
				at_walls += std::fabs(x - 19.5) < 1e-12 || std::fabs(x - 20.5) < 1e-12 ||
					    std::fabs(x - 69.5) < 1e-12 || std::fabs(x - 70.5) < 1e-12;
				ok = ok && p[i].state[1] == c50.y;
			}
		ok = ok && at_walls == seq.size() - 1;
		const Route r = route_of(c50, seq);
		ok = ok && route_name(c50, r) == seq && route_fault(c50, r, 0.0).empty() && route_fault(c50, r, 0.5).empty();
		if (!ok) {
			all = false;
			why += seq + " " + route_fault(c50, r, 0.0) + " ";
		}
	}
	check(all, "fixed sequences: their modes (takeoff and landing on the ground), rest at the ends, "
		   "switch points a cell from the walls", "wrong: " + why);
	// With a body and margin of 0.44 m the cells touching a wall's edge are
	// not clear: the switch points move a cell further, into clear cells.
	std::string at;
	for (const Waypoint &w : sequence_plan(profile_of(s50, 0.44), "DFDFD", 0.0))
		if (w.guard && w.mode == HYLO_MODE_GROUND)
			at += std::to_string(static_cast<int>(std::lround(10 * w.state[0]))) + " ";
	check(at == "190 210 690 710 ", "body and margin 0.44 m: DFDFD switches 1 m from the walls (19, 21, 69, 71 m)",
	      "at (dm): " + at);
	// The flights' guesses keep clear of the walls' top edges: within 0.5 m
	// of a wall a guess is at least 0.94 m above the platform (the flight
	// clearance 0.5 m plus the 0.44 m), on the straight lines between its
	// waypoints too (the corridors are built along them).
	std::string low;
	for (const std::string seq : {"F", "DF", "DFD", "FDF", "DFDF", "DFDFD"})
		low += low_at_edges(profile_of(s50, 0.44), sequence_plan(profile_of(s50, 0.44), seq, 0.0), seq);
	check(low.empty(), "the flights' guesses pass the walls' top edges at least 0.94 m above the platforms", low);
	check(route_of(c50, "DFD(floor1)FD") == route_of(c50, "DFDFD") && routes(c50).size() == 2 &&
		      route_name(c50, routes(c50)[1]) == "DFDFD",
	      "one chasm: its floor's drive named or not, two routes driving at both ends (DFD, DFDFD)");

	// Two chasms made from the 30 m one.
	const hylo::scene::Scene t = chasms(s30, c30, {30, 20, 30});
	const Profile c2 = profile_of(t, 0.44);   // the Drivocopter's body, margin and pad
	// Its columns: chasm_030's up to the far wall (the first floor is 30 m
	// already), 20 m of copies of the platform's last column, chasm_030's
	// floor and goal platform again.
	bool cells = t.nx == s30.nx + 100 && t.name == "chasm_030_020_030";
	for (int iy = 0; cells && iy < t.ny; iy++)
		for (int ix = 0; ix < t.nx; ix++) {
			const int from = ix < 100 ? ix : ix < 140 ? 39 : ix - 100;
			const size_t k = static_cast<size_t>(iy * t.nx + ix), f = static_cast<size_t>(iy * s30.nx + from);
			cells = cells && t.terrain[k] == s30.terrain[f] && t.height_m[k] == s30.height_m[f];
		}
	check(cells && c2.walls == std::vector<double>{20, 50, 70, 100} &&
		      c2.heights == std::vector<double>{6, 0, 6, 0, 6} && c2.x_start == 10 && c2.x_goal == 110,
	      "chasm_030 made into 30, 20, 30: walls at 20, 50, 70, 100 m, a 6 m platform between two floors, "
	      "the goal 50 m on");

	const std::vector<std::string> names = {"DFD",
						"DFD(floor1)FD",
						"DFD(mid1)FD",
						"DFD(floor2)FD",
						"DFD(floor1)FD(mid1)FD",
						"DFD(floor1)FD(floor2)FD",
						"DFD(mid1)FD(floor2)FD",
						"DFD(floor1)FD(mid1)FD(floor2)FD"};
	std::vector<std::string> got;
	bool round_trip = true;
	for (const Route &r : routes(c2)) {
		got.push_back(route_name(c2, r));
		round_trip = round_trip && route_of(c2, got.back()) == r;
	}
	check(got == names && round_trip, "two chasms: 8 routes, each landing on its own subset of floor1, mid1, floor2",
	      got.size() == names.size() ? got[1] : std::to_string(got.size()) + " routes");

	all = true;
	why.clear();
	std::vector<Route> every = routes(c2);
	for (const std::string extra : {"F", "DF", "FD", "FD(mid1)F", "DFD(floor2)F"})
		every.push_back(route_of(c2, extra));
	for (const Route &r : every)
		for (double lambda : {0.0, 0.5})
			if (std::string f = route_fault(c2, r, lambda) +
					    low_at_edges(c2, sequence_plan(c2, r, lambda), "");
			    !f.empty()) {
				all = false;
				why += route_name(c2, r) + " at " + std::to_string(lambda) + ": " + f + "; ";
			}
	check(all, "two chasms: every route's plan drives on its segments only, its flights above every wall top "
		   "they pass (0.94 m over each wall's edge, between waypoints too), switch points a margin from "
		   "the walls", why);

	check(throws(c2, "DFDFD") && throws(c2, "DFD(floor3)FD") && throws(c2, "DFD(floor2)FD(floor1)FD") &&
		      throws(c2, "DDF") && throws(c2, "D") && throws(c2, "") && throws(c2, "D(start)FD") &&
		      throws(c2, "DFD(floor1FD") && throws(c2, "DXD"),
	      "route names that are ambiguous, unknown, backwards or not alternating are refused");
	bool refused = false;
	try {
		chasms(t, c2, {30});
	} catch (const std::invalid_argument &) {
		refused = true;
	}
	check(refused, "chasms() only from a one-chasm scene");
	return tap_finish();
}
