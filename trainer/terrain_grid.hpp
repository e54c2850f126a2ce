// The map as the smoother reads it: the parts of a map_t it needs, and the
// cell under a point. The corridors, the switch guards, the domain check and
// the clearance check all read this one type (the onboard code's own map,
// for the clearance rules, is made from it: trainer/clearance.hpp).
#ifndef HYLO_TRAINER_TERRAIN_GRID_HPP
#define HYLO_TRAINER_TERRAIN_GRID_HPP

#include <cstdint>
#include <vector>

#include "hylo/map.h"

namespace hylo::trainer {

// The parts of a map_t the smoother reads.
struct TerrainGrid {
	int nx = 0, ny = 0;
	double resolution_m = 1, origin_x_m = 0, origin_y_m = 0;
	std::vector<int8_t> terrain;   // map_t TERRAIN_*: 0 obstacle, 1 ground, 2 water
	std::vector<float> height_m;
	double max_step_m = 0.2;       // map_t max_step_m: a larger height step is a wall
	double ceiling_m = 1e4;        // map_t ceiling_m [m]
};

// The grid of anything that names its fields as map_t does (hylo::map_t, the
// scene tool's Scene).
template <class Map>
TerrainGrid terrain_grid(const Map &m)
{
	TerrainGrid g;
	g.nx = m.nx;
	g.ny = m.ny;
	g.resolution_m = m.resolution_m;
	g.origin_x_m = m.origin_x_m;
	g.origin_y_m = m.origin_y_m;
	g.terrain = m.terrain;
	g.height_m = m.height_m;
	g.max_step_m = m.max_step_m;
	g.ceiling_m = m.ceiling_m;
	return g;
}

// Flights keep this high above the terrain [m]: the onboard planner's.
constexpr double kAirClearanceM = HYLO_AIR_CLEARANCE_M;

// Terrain classes (map_t TERRAIN_*).
constexpr int8_t kGround = HYLO_TERRAIN_GROUND, kWater = HYLO_TERRAIN_WATER;

// The cell holding a point: on the map or not, and its index iy * nx + ix.
struct GridCell {
	bool inside = false;
	int index = 0;
};

inline GridCell cell_at(const TerrainGrid &m, double x, double y)
{
	double fx = (x - m.origin_x_m) / m.resolution_m, fy = (y - m.origin_y_m) / m.resolution_m;
	if (!(fx >= 0 && fy >= 0 && fx < m.nx && fy < m.ny))
		return {};
	return {true, static_cast<int>(fy) * m.nx + static_cast<int>(fx)};
}

}  // namespace hylo::trainer

#endif
