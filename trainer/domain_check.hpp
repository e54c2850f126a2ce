// Whether a smoothed trajectory stays in its map's domain (docs/smoothing.md,
// "The domain check"): every fallback step's trajectory is checked at its
// knots and midpoints before it is taken.
#ifndef HYLO_TRAINER_DOMAIN_CHECK_HPP
#define HYLO_TRAINER_DOMAIN_CHECK_HPP

#include <string>

#include "trainer/solution.hpp"
#include "trainer/terrain_grid.hpp"

namespace hylo::trainer {

// How far a trajectory leaves its map's domain: for every knot and
// midpoint, a ground (marine) state's distance from the nearest ground
// (water) cell, a flight's depth below the terrain under it; the worst over
// the trajectory. Off the map counts as infinitely far. Modes without a
// terrain class (the double integrator's) are not checked.
struct DomainCheck {
	double worst_m = 0;       // 0: inside everywhere
	int phase = -1;           // where it is worst
	hylo_mode mode = HYLO_MODE_NONE;
	double t_s = 0, x_m = 0, y_m = 0;
	double reach_m = 0;       // how far it looks for a cell of the mode's class
	std::string text() const;   // "phase 1 (marine) at t = 3.2 s, (4.1, 7.0) m: 0.9 m from water"
};
DomainCheck domain_check(const MultiPhaseSolution &s, const TerrainGrid &map);

// A trajectory may leave its domain by this much and still be accepted:
// one cell (the switch points sit on cell edges, the map is a raster).
double domain_tolerance_m(const TerrainGrid &map);

}  // namespace hylo::trainer

#endif
