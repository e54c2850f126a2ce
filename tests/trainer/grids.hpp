// Maps for the smoother's tests: they start from flat ground and draw on it.
#ifndef HYLO_TESTS_TRAINER_GRIDS_HPP
#define HYLO_TESTS_TRAINER_GRIDS_HPP

#include <cstddef>

#include "trainer/terrain_grid.hpp"

// nx x ny cells of resolution_m, all ground at height 0, origin (0, 0).
inline hylo::trainer::TerrainGrid flat_ground(int nx, int ny, double resolution_m = 1)
{
	hylo::trainer::TerrainGrid g;
	g.nx = nx;
	g.ny = ny;
	g.resolution_m = resolution_m;
	const size_t cells = static_cast<size_t>(nx) * static_cast<size_t>(ny);
	g.terrain.assign(cells, hylo::trainer::kGround);
	g.height_m.assign(cells, 0.0f);
	return g;
}

#endif
