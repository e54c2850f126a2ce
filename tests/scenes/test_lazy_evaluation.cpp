// Every committed scene, one plan (A*) there and back: every edge the search
// evaluated could lie on a path no dearer than the plan (the cost of its
// tail + its bound + the heuristic of its head): the search evaluates a
// deferred group's edges only as their own keys come first (docs/planner.md,
// "The search"). Evaluating every wanted edge of a group at once breaks it on
// every Drivocopter and Ambot scene. The greedy walk's edges, evaluated
// before the search, are left out. TAP; run from the repository's root (scene
// files as arguments instead).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "hylo/planner.h"
extern "C" {
#include "src/planner_internal.h"
}
#include "tests/tap.hpp"
#include "tests/scenes/scene_suite.hpp"
#include "tools/scene/committed.hpp"
#include "tools/scene/planner_view.hpp"

namespace {

struct Lazy {
	unsigned checked = 0, above = 0;
	double worst = 0;   // the largest f over the plan's cost
};

// The cached edges of every node the search expanded, off the walk.
Lazy check_edges(const hylo_planner *pl, double plan_cost)
{
	Lazy out;
	const hylo_roadmap *rm = hylo_planner_roadmap(pl);
	for (uint32_t u = 0; u < rm->n_nodes; u++) {
		bool on_walk = false;
		for (uint32_t w = 0; w < pl->walk_len; w++)
			on_walk |= pl->walk_path[w] == u;
		if (on_walk || !hylo_search_closed(&pl->search, u))
			continue;
		const uint32_t i = rm->node_pos[u], ci = u - rm->pos[i].node_base;
		const double g = hylo_search_cost(&pl->search, u);
		hylo_real tail[HYLO_XS_DIM];
		hylo_planner_node_state(pl, i, ci, tail);
		uint32_t n_adj = 0;
		const uint32_t *adj = hylo_planner_neighbours(pl, i, &n_adj);
		for (uint32_t k = 0; k < n_adj; k++) {
			const hylo_real *cost =
				hylo_edge_cache_group(const_cast<hylo_edge_cache *>(&pl->cache), rm, u, k, 0);
			if (!cost)
				continue;
			const uint32_t j = adj[k];
			hylo_pair_bound pb;
			hylo_planner_pair_bound(const_cast<hylo_planner *>(pl), i, j, &pb);
			for (uint32_t c = 0; c < rm->pos[j].n_combos; c++) {
				if (std::isnan(cost[c]))
					continue;
				hylo_real head[HYLO_XS_DIM];
				hylo_planner_node_state(pl, j, c, head);
				const double f = g + hylo_planner_bound(&pb, ci, tail, c, head) +
						 hylo_planner_h(pl, rm->pos[j].node_base + c);
				out.above += !(f <= plan_cost * (1 + 1e-9));
				out.worst = std::fmax(out.worst, f / plan_cost);
				out.checked++;
			}
		}
	}
	return out;
}

}  // namespace

int main(int argc, char **argv)
{
	SceneSuite suite;
	if (!open_suite(argc, argv, suite))
		return 1;
	hylo_planner *pl = suite.committed->get();
	const std::unique_ptr<hylo_plan> &plan = suite.plan;
	unsigned checked = 0;
	for (const std::string &path : suite.scenes) {
		const hylo::scene::Scene sc = hylo::scene::load(path);
		hylo_goal there = hylo::scene::goal_of(sc);
		there.alternatives = 1;
		there.algorithm = HYLO_ASTAR;
		plan_there_and_back(suite, sc, there, [&](const std::string &name, const hylo_goal &) {
			const bool planned = plan->status == HYLO_OK && plan->outcome == HYLO_FOUND;
			check(planned, name + ": planned", plan->reason.text);
			if (!planned)
				return;
			const Lazy l = check_edges(pl, plan->total_cost);
			check(l.above == 0, name + ": every edge evaluated could lie on a path no dearer than the plan",
			      std::to_string(l.above) + " of " + std::to_string(l.checked) + " above, the worst at " +
				      std::to_string(l.worst) + " times the plan's cost");
			checked += l.checked;
		});
	}
	check(checked > 10000, "the search's edges checked", std::to_string(checked) + " edges");
	return tap_finish();
}
