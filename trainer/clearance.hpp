// The exact clearance check of a smoothed trajectory (docs/smoothing.md,
// "Clearance"): every knot and midpoint, and points between them on the
// collocation's own cubic (positions and their kinematic velocities at the
// knots), are measured against the map's hazards with the onboard
// definition (hylo_hazard_distance, hylo_domain_contains), so the planner,
// the smoother and this check agree on what "inside" means.
#ifndef HYLO_TRAINER_CLEARANCE_HPP
#define HYLO_TRAINER_CLEARANCE_HPP

#include <memory>
#include <string>

#include "hylo/map.h"
#include "trainer/solution.hpp"
#include "trainer/terrain_grid.hpp"

namespace hylo::trainer {

struct ClearanceCheck {
	bool safe = true;            // every point keeps clearance >= margin and lies in its mode's domain
	                             // (both to kCheckToleranceM)
	double body_radius_m = 0, margin_m = 0;
	// The smallest distance between the body and a hazard of its mode [m],
	// and where; capped at margin + kClearanceReachM (nothing nearer).
	double min_clearance_m = 0;
	int phase = -1;              // -1: no phase has hazards (the double integrator)
	hylo_mode mode = HYLO_MODE_NONE;
	double t_s = 0, x_m = 0, y_m = 0, z_m = 0;
	// The first point found outside its mode's domain (phase -1: none).
	int outside_phase = -1;
	double outside_t_s = 0, outside_x_m = 0, outside_y_m = 0, outside_z_m = 0;
	int points = 0;              // points measured
	// "clearance 0.23 m >= margin 0.1 m (phase 2, flight, t = 3.1 s at (4.0, 2.0, 3.5) m)",
	// or "not safe: ..." naming the point.
	std::string text() const;
};

// The map as the onboard code holds it (hylo_map_ingest; a few MB), for its
// domain, hazard and clearance functions; a ceiling that is not finite
// becomes one far above the highest cell. Throws std::invalid_argument
// for a map the onboard code refuses, naming why.
std::unique_ptr<hylo_map> onboard_map(const TerrainGrid &grid);

// How far beyond the margin the check looks for hazards [m].
constexpr double kClearanceReachM = 2.0;
// Points within this of their domain, and clearances within this of the
// margin, pass [m]: optimal trajectories sit on their bounds, which the
// solver meets to about 1e-8.
constexpr double kCheckToleranceM = 1e-6;

// Checks s on map for a body of body_radius_m and the margin, with
// between_knots points on the cubic between consecutive knots.
ClearanceCheck check_clearance(const MultiPhaseSolution &s, const TerrainGrid &map, double body_radius_m,
			       double margin_m, int between_knots = 10);

}  // namespace hylo::trainer

#endif
