// Scene files (scenes/*.yaml, format in scenes/README.md): a map and a
// default goal. Loading validates everything; errors name the file and line.
#ifndef HYLO_TOOLS_SCENE_HPP
#define HYLO_TOOLS_SCENE_HPP

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace hylo::scene {

// A load or validation error: "FILE:LINE: what".
class Error : public std::runtime_error {
public:
	using std::runtime_error::runtime_error;
};

struct State {
	int mode = 0;                    // goal_t.MODE_*
	std::array<double, 6> x{};       // sampled coordinates, zero-padded
};

struct Goal {
	State start, goal;
	int algorithm = 0;               // goal_t.ALGORITHM_*
	int64_t seed = 1;
	double spacing_m = 0, air_spacing_m = 0, guard_spacing_m = 0;
	double connect_radius_m = 0, air_connect_radius_m = 0;
	std::vector<double> speeds_mps, headings_rad, air_speeds_mps;
	double time_budget_ms = 0;
	double suboptimality = 0;        // w >= 1, 0: the optimum
	int32_t max_expansions = 0;
	int alternatives = 0;            // K distinct mode sequences; 1: the plan only, 0: the default (3)
	double alternatives_within = 0;  // >= 1, 0: the planner's default
};

struct Scene {
	std::string path, name, description;
	std::string robot;
	int64_t map_id = 1;
	int32_t nx = 0, ny = 0;
	double resolution_m = 0, origin_x_m = 0, origin_y_m = 0;
	double ceiling_m = 0, max_step_m = 0;
	std::vector<int8_t> terrain;     // nx * ny, index iy * nx + ix
	std::vector<float> height_m;
	bool has_goal = false;
	Goal goal;
	// render: the 3-D camera of hylo-render (azimuth, elevation [deg],
	// distance [m]; 0 = fit the map).
	double camera_azimuth_deg = -60, camera_elevation_deg = 28, camera_distance_m = 0;
};

// Loads and validates a scene file. Throws Error.
Scene load(const std::string &path);

// Mode number of a mode name ("ground", ...) or 0; its sampled dimension.
int mode_of(const std::string &name);
int mode_dim(int mode);
const char *mode_name(int mode);

// Parses "MODE:x1,x2,..." (e.g. "ground:2,16,0,0"). Throws Error naming what.
State parse_state(const std::string &text, const std::string &what);

}  // namespace hylo::scene

#endif
