// Case study 3's chasms (tools/casestudies/chasm.cpp): the walls found in the
// committed scenes, a chasm widened from a narrower one equal to the
// committed wider scene (the crossover solves on widths in between), and the
// fixed sequences' plans: their mode sequence, ends at rest on the start and
// goal, switch points at the walls. Prints TAP.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/tap.hpp"
#include "tools/casestudies/chasm.hpp"

using namespace hylo::casestudies;
using hylo::trainer::mode_number;
using hylo::trainer::Waypoint;

int main()
{
	const hylo::scene::Scene s50 = hylo::scene::load("scenes/chasm_050.yaml");
	const hylo::scene::Scene s70 = hylo::scene::load("scenes/chasm_070.yaml");
	const Chasm c50 = chasm_of(s50, 0);
	check(c50.e1 == 20 && c50.e2 == 70 && c50.h_platform == 6 && c50.h_floor == 0 && c50.x_start == 10 &&
		      c50.x_goal == 80,
	      "chasm_050: walls at 20 and 70 m, platforms 6 m over the floor, start and goal 10 m back",
	      "walls " + std::to_string(c50.e1) + ", " + std::to_string(c50.e2));

	const hylo::scene::Scene w = widened(s50, c50, 20);
	check(w.nx == s70.nx && w.terrain == s70.terrain && w.height_m == s70.height_m &&
		      w.goal.goal.x == s70.goal.goal.x && w.goal.start.x == s70.goal.start.x && w.name == "chasm_070",
	      "chasm_050 widened by 20 m is chasm_070, cell for cell");
	const Chasm c51 = chasm_of(widened(s50, c50, 1), 0);
	check(c51.e1 == 20 && c51.e2 == 71 && c51.x_goal == 81, "widened by 1 m: the far wall and the goal move 1 m");

	bool all = true;
	std::string why;
	for (const std::string seq : {"F", "DF", "DFD", "FDF", "DFDF", "DFDFD"}) {
		std::vector<Waypoint> p = sequence_plan(c50, seq, 0.0);
		const Waypoint &a = p.front(), &b = p.back();
		bool ok = letters(p) == (seq.front() == 'F' ? "D" : "") + seq + (seq.back() == 'F' ? "D" : "");
		ok = ok && a.mode == mode_number("ground") && a.state[0] == 10 && a.state[2] == 0;
		ok = ok && b.mode == mode_number("ground") && b.state[0] == 80 && b.state[2] == 0;
		// Switch points (ground guards) between the ends: one per change of
		// mode in seq, each a cell from a wall.
		size_t at_walls = 0;
		for (size_t i = 1; i + 1 < p.size(); i++)
			if (p[i].guard && p[i].mode == mode_number("ground")) {
				double x = p[i].state[0];
				at_walls += std::fabs(x - 19.5) < 1e-12 || std::fabs(x - 20.5) < 1e-12 ||
					    std::fabs(x - 69.5) < 1e-12 || std::fabs(x - 70.5) < 1e-12;
				ok = ok && p[i].state[1] == c50.y;
			}
		ok = ok && at_walls == seq.size() - 1;
		if (!ok) {
			all = false;
			why += seq + " ";
		}
	}
	check(all, "fixed sequences: their modes (takeoff and landing on the ground), rest at the ends, "
		   "switch points a cell from the walls", "wrong: " + why);
	// With a body and margin of 0.44 m the cells touching a wall's edge are
	// not clear: the switch points move a cell further, into clear cells.
	std::string at;
	for (const Waypoint &w : sequence_plan(chasm_of(s50, 0.44), "DFDFD", 0.0))
		if (w.guard && w.mode == mode_number("ground"))
			at += std::to_string(static_cast<int>(std::lround(10 * w.state[0]))) + " ";
	check(at == "190 210 690 710 ", "body and margin 0.44 m: DFDFD switches 1 m from the walls (19, 21, 69, 71 m)",
	      "at (dm): " + at);
	// The flights' guesses keep clear of the walls' top edges: within 0.5 m
	// of a wall a guess is at least 0.94 m above the platform (the flight
	// clearance 0.5 m plus the 0.44 m), on the straight lines between its
	// waypoints too (the corridors are built along them).
	std::string low;
	for (const std::string seq : {"F", "DF", "DFD", "FDF", "DFDF", "DFDFD"}) {
		const std::vector<Waypoint> p = sequence_plan(chasm_of(s50, 0.44), seq, 0.0);
		for (size_t i = 1; i < p.size(); i++) {
			if (p[i].mode != mode_number("flight") || p[i - 1].mode != mode_number("flight"))
				continue;
			for (int k = 0; k <= 20; k++) {
				const double x = p[i - 1].state[0] + (p[i].state[0] - p[i - 1].state[0]) * k / 20;
				const double z = p[i - 1].state[2] + (p[i].state[2] - p[i - 1].state[2]) * k / 20;
				if ((std::fabs(x - 20) < 0.5 || std::fabs(x - 70) < 0.5) && z < 6.94) {
					low += seq + " at (" + std::to_string(x) + ", " + std::to_string(z) + ") ";
					break;
				}
			}
		}
	}
	check(low.empty(), "the flights' guesses pass the walls' top edges at least 0.94 m above the platforms", low);
	return tap_finish();
}
