// A scene (scene.hpp) as the onboard planner's inputs: its map as a
// hylo_map_view and its goal as a hylo_goal. Both point into the scene,
// which must outlive them.
#ifndef HYLO_TOOLS_PLANNER_VIEW_HPP
#define HYLO_TOOLS_PLANNER_VIEW_HPP

#include <algorithm>
#include <utility>

#include "hylo/planner.h"
#include "tools/scene/scene.hpp"

namespace hylo::scene {

inline hylo_map_view map_view(const Scene &sc)
{
	hylo_map_view v{};
	v.map_id = sc.map_id;
	v.robot = sc.robot.c_str();
	v.nx = sc.nx;
	v.ny = sc.ny;
	v.resolution = sc.resolution_m;
	v.origin_x = sc.origin_x_m;
	v.origin_y = sc.origin_y_m;
	v.ceiling = sc.ceiling_m;
	v.max_step = sc.max_step_m;
	v.n_cells = sc.nx * sc.ny;
	v.terrain = sc.terrain.data();
	v.height = sc.height_m.data();
	return v;
}

// Copies a scene's grid into a goal's and returns its count; a grid longer
// than HYLO_MAX_GRID is not copied, its count stays for the planner to refuse.
inline uint32_t sampling_grid(hylo_real (&dst)[HYLO_MAX_GRID], const std::vector<double> &v)
{
	if (v.size() <= HYLO_MAX_GRID)
		std::copy(v.begin(), v.end(), dst);
	return static_cast<uint32_t>(v.size());
}

inline hylo_goal goal_of(const Scene &sc)
{
	const Goal &g = sc.goal;
	hylo_goal q{};
	q.request_id = 1;
	q.algorithm = g.algorithm;
	q.start_mode = g.start.mode;
	q.goal_mode = g.goal.mode;
	for (int k = 0; k < HYLO_XS_DIM; k++) {
		q.start[k] = g.start.x[static_cast<size_t>(k)];
		q.goal[k] = g.goal.x[static_cast<size_t>(k)];
	}
	q.sampling.seed = static_cast<uint64_t>(g.seed);
	q.sampling.spacing = g.spacing_m;
	q.sampling.air_spacing = g.air_spacing_m;
	q.sampling.guard_spacing = g.guard_spacing_m;
	q.sampling.connect_radius = g.connect_radius_m;
	q.sampling.air_connect_radius = g.air_connect_radius_m;
	q.sampling.n_speeds = sampling_grid(q.sampling.speeds, g.speeds_mps);
	q.sampling.n_headings = sampling_grid(q.sampling.headings, g.headings_rad);
	q.sampling.n_air_speeds = sampling_grid(q.sampling.air_speeds, g.air_speeds_mps);
	q.time_budget_ms = g.time_budget_ms;
	q.max_expansions = static_cast<uint64_t>(g.max_expansions);
	q.suboptimality = g.suboptimality;
	// As the node reads it from goal_t: 0 is the default.
	q.alternatives = g.alternatives == 0 ? HYLO_DEFAULT_ALTERNATIVES : static_cast<uint32_t>(g.alternatives);
	q.alternatives_within = g.alternatives_within;
	return q;
}

// The same goal the other way: start and goal (modes and states) swapped.
inline hylo_goal way_back(const hylo_goal &g)
{
	hylo_goal b = g;
	std::swap(b.start_mode, b.goal_mode);
	std::swap_ranges(b.start, b.start + HYLO_XS_DIM, b.goal);
	return b;
}

}  // namespace hylo::scene

#endif
