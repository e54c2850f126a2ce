// Every committed scene (scenes/*.yaml), planned with the committed models
// there and back (start and goal swapped): the planner evaluates no edge
// outside its model's trained region (hylo_plan.n_untrained, hylo/region.h).
// And a start whose velocity the flight model never saw is refused.
// TAP; run from the repository's root (scene files as arguments instead).
#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "hylo/planner.h"
#include "tests/tap.hpp"
#include "tests/scenes/scene_suite.hpp"
#include "tools/scene/committed.hpp"
#include "tools/scene/planner_view.hpp"

int main(int argc, char **argv)
{
	SceneSuite suite;
	if (!open_suite(argc, argv, suite))
		return 1;
	hylo_planner *pl = suite.committed->get();
	const std::unique_ptr<hylo_plan> &plan = suite.plan;
	const std::vector<std::string> &scenes = suite.scenes;
	for (const std::string &path : scenes) {
		const hylo::scene::Scene sc = hylo::scene::load(path);
		plan_there_and_back(suite, sc, hylo::scene::goal_of(sc), [&](const std::string &name, const hylo_goal &) {
			const bool planned = plan->status == HYLO_OK && plan->outcome == HYLO_FOUND &&
					     plan->n_edges_evaluated > 0;
			check(planned, name + ": planned", plan->reason.text);
			check(planned && plan->n_untrained == 0,
			      name + ": every evaluated edge inside its model's trained region",
			      std::to_string(plan->n_untrained) + " of " + std::to_string(plan->n_edges_evaluated) +
				      " outside");
		});
	}
	// A flight start descending at 2.7 m/s (the training velocities are
	// level) above a chasm scene's start: refused, naming vz; level, planned.
	const hylo::scene::Scene sc = hylo::scene::load("scenes/chasm_050.yaml");
	const hylo_map_view v = hylo::scene::map_view(sc);
	hylo_goal g = hylo::scene::goal_of(sc);
	const int ix = static_cast<int>((g.start[0] - sc.origin_x_m) / sc.resolution_m),
		  iy = static_cast<int>((g.start[1] - sc.origin_y_m) / sc.resolution_m);
	g.start_mode = HYLO_MODE_FLIGHT;
	g.start[2] = sc.height_m[static_cast<size_t>(iy * sc.nx + ix)] + 3;
	g.start[3] = 2;
	g.start[5] = -2.7;
	hylo_planner_set_map(pl, &v);
	hylo_planner_plan(pl, &g, plan.get());
	const std::string why = plan->reason.text;
	check(plan->status == HYLO_E_BAD_VALUE &&
		      why.find("start vz = -2.7 m/s is outside the flight model's training range [0, 0] m/s") !=
			      std::string::npos,
	      "chasm_050: a flight start descending at 2.7 m/s is a bad request naming vz", why);
	g.start[5] = 0;
	hylo_planner_plan(pl, &g, plan.get());
	check(plan->status == HYLO_OK && plan->outcome == HYLO_FOUND && plan->n_untrained == 0,
	      "chasm_050: the same start flying level is planned", plan->reason.text);
	return tap_finish();
}
