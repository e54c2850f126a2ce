// Every committed scene (scenes/*.yaml), planned there and back with the
// committed models and the default margin, asking for alternatives: every
// waypoint of every path returned, and every edge sampled every 2 cm, keeps
// its robot's body (trainer/params/<robot>.yaml, through the registry) plus
// HYLO_DEFAULT_MARGIN_M from the nearest hazard of its mode, measured
// exactly by hylo_hazard_distance (hylo/clearance.h). Switch edges (a guard
// point and its twin) are checked at both ends, each in its own mode.
// TAP; run from the repository's root (scene files as arguments instead).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "hylo/clearance.h"
#include "hylo/planner.h"
#include "node/registry.h"
#include "tests/tap.hpp"
#include "tests/scenes/scene_suite.hpp"
#include "tools/scene/committed.hpp"
#include "tools/scene/planner_view.hpp"

namespace {

// Samples along an edge [m]: far finer than a cell (0.05 m and more).
constexpr double kStep = 0.02;
// Clearances are measured up to this [m] (hylo_hazard_distance's reach).
constexpr double kReach = 1.0;

struct Worst {
	double clearance = HUGE_VAL;   // hazard distance minus the body radius [m]
	hylo_point where{};
	hylo_mode mode = HYLO_MODE_NONE;
};

hylo_point point_of(const hylo_map *m, hylo_mode mode, const hylo_real *xs)
{
	hylo_point p{xs[0], xs[1], 0};
	if (mode == HYLO_MODE_FLIGHT)
		p.z = xs[2];
	else if (mode == HYLO_MODE_GROUND || mode == HYLO_MODE_MARINE)
		p.z = hylo_map_height(m, xs[0], xs[1]);
	return p;
}

void measure(const hylo_map *m, hylo_mode mode, hylo_point p, double body, double reach, Worst &w)
{
	const double c = hylo_hazard_distance(m, mode, p, reach) - body;
	if (c < w.clearance)
		w = Worst{c, p, mode};
}

// The least clearance over the waypoints and (same-mode) edges of plan.
Worst path_clearance(const hylo_map *m, const hylo_plan &plan, double body, double reach)
{
	Worst w;
	for (uint32_t k = 0; k < plan.n_waypoints; k++) {
		const hylo_mode mode = static_cast<hylo_mode>(plan.mode[k]);
		const hylo_point a = point_of(m, mode, plan.state[k]);
		measure(m, mode, a, body, reach, w);
		if (k + 1 == plan.n_waypoints || plan.mode[k + 1] != plan.mode[k])
			continue;
		const hylo_point b = point_of(m, mode, plan.state[k + 1]);
		const double len = std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
					     (b.z - a.z) * (b.z - a.z));
		const int n = static_cast<int>(std::ceil(len / kStep));
		for (int i = 1; i < n; i++) {
			const double t = static_cast<double>(i) / n;
			hylo_point p{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
			if (mode != HYLO_MODE_FLIGHT)
				p.z = hylo_map_height(m, p.x, p.y);
			measure(m, mode, p, body, reach, w);
		}
	}
	return w;
}

std::string describe(const Worst &w)
{
	char buf[160];
	std::snprintf(buf, sizeof buf, "least clearance %.4f m (%s at %.3f, %.3f, %.3f)", w.clearance,
		      hylo_mode_str(w.mode), w.where.x, w.where.y, w.where.z);
	return buf;
}

}  // namespace

int main(int argc, char **argv)
{
	SceneSuite suite;
	if (!open_suite(argc, argv, suite))
		return 1;
	hylo_planner *pl = suite.committed->get();
	const std::unique_ptr<hylo_plan> &plan = suite.plan;
	const std::vector<std::string> &scenes = suite.scenes;
	const double margin = HYLO_DEFAULT_MARGIN_M;
	for (const std::string &path : scenes) {
		const hylo::scene::Scene sc = hylo::scene::load(path);
		const hylo_map_view v = hylo::scene::map_view(sc);
		const hylo_registry_body *b = hylo_registry_body_of(sc.robot.c_str());
		const double body = b ? b->radius_m : 0;
		hylo_goal there = hylo::scene::goal_of(sc);
		there.alternatives = 3;
		const hylo_goal back = hylo::scene::way_back(there);
		hylo_planner_set_map(pl, &v);
		check(std::fabs(hylo_planner_clearance(pl) - (body + margin)) < 1e-12,
		      sc.name + ": the planner keeps the body (" + std::to_string(body) + " m) + the margin",
		      std::to_string(hylo_planner_clearance(pl)) + " m");
		for (const hylo_goal *g : {static_cast<const hylo_goal *>(&there), &back}) {
			const std::string name = sc.name + (g == &there ? "" : " (back)");
			hylo_planner_plan(pl, g, plan.get());
			const bool planned = plan->status == HYLO_OK && plan->outcome == HYLO_FOUND;
			check(planned, name + ": planned", plan->reason.text);
			const uint32_t n = planned ? plan->n_alternatives : 0;
			for (uint32_t k = 0; k < n; k++) {
				hylo_planner_alternative(pl, k, plan.get());
				const Worst w = path_clearance(&pl->map, *plan, body, body + kReach);
				check(w.clearance >= margin - 1e-9,
				      name + ": path " + std::to_string(k) + " (" +
					      std::to_string(plan->n_waypoints) +
					      " waypoints) keeps the body + margin, edges sampled every 2 cm",
				      describe(w));
				std::printf("# %s, %.1f J: %s\n", name.c_str(), plan->total_cost,
					    describe(w).c_str());
			}
		}
	}
	return tap_finish();
}
