// What the committed-scene tests share: a planner with every committed model,
// a plan to fill, and the scene files to plan on (the arguments, or every
// committed scene). TAP; run from the repository's root.
#ifndef TESTS_SCENES_SCENE_SUITE_HPP
#define TESTS_SCENES_SCENE_SUITE_HPP

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "hylo/planner.h"
#include "tests/tap.hpp"
#include "tools/scene/committed.hpp"
#include "tools/scene/planner_view.hpp"

struct SceneSuite {
	std::unique_ptr<hylo::scene::CommittedPlanner> committed;
	std::unique_ptr<hylo_plan> plan{new hylo_plan};
	std::vector<std::string> scenes;
};

// Makes the planner and lists the scenes (at least 8 committed ones: a
// check); false, after a failed check, when the planner cannot be made.
inline bool open_suite(int argc, char **argv, SceneSuite &s)
{
	try {
		s.committed.reset(new hylo::scene::CommittedPlanner);
	} catch (const std::exception &e) {
		check(false, "a planner with every committed model", e.what());
		return false;
	}
	s.scenes.assign(argv + 1, argv + argc);
	if (s.scenes.empty())
		s.scenes = hylo::scene::committed_scenes();
	check(s.scenes.size() >= 8, "the committed scenes", std::to_string(s.scenes.size()) + " scene files");
	return true;
}

// Plans scene sc from `there` and back (start and goal swapped), each on
// the scene's map set anew (no edge cost kept from the other), and calls
// visit(name, goal) after each with the plan in s.plan.
template <class Visit>
void plan_there_and_back(SceneSuite &s, const hylo::scene::Scene &sc, const hylo_goal &there, Visit visit)
{
	const hylo_map_view v = hylo::scene::map_view(sc);
	const hylo_goal back = hylo::scene::way_back(there);
	for (const hylo_goal *g : {&there, &back}) {
		hylo_planner_set_map(s.committed->get(), &v);
		hylo_planner_plan(s.committed->get(), g, s.plan.get());
		visit(sc.name + (g == &there ? "" : " (back)"), *g);
	}
}

#endif
