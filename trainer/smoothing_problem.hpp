// The multi-phase problem of a plan (paper section III.A.3; docs/smoothing.md,
// "The problem"): the plan's waypoints are split into phases at its guard
// points, one multi-phase collocation problem with that mode sequence, the
// switch points free to slide along their guards, switching costs included.
//
// The map's domain, with the robot's body and a margin, is enforced along
// each phase by a safe corridor (trainer/corridor.hpp; docs/smoothing.md,
// "Clearance"): axis-aligned boxes of cells that keep body + margin clear of
// the mode's hazards, each bounding the knots of its part of the phase. A
// shore switch point slides on the piece of shore where the ground and the
// water corridors meet (the fitted straight shoreline when they do not); a
// takeoff or landing point on the clear level ground around it
// (trainer/map_guards.hpp). A flight crossing a wall (a height step over
// max_step) is also cut there into two phases that meet above the wall's top
// plus the flight clearance. Where the plan itself passes too close for a
// box, the corridor gives less clearance there, or none, and the problem's
// notes say where. A plan that takes off at its first waypoint (lands at its
// last) starts (ends) with the hover above it, no ground phase.
#ifndef HYLO_TRAINER_SMOOTHING_PROBLEM_HPP
#define HYLO_TRAINER_SMOOTHING_PROBLEM_HPP

#include <memory>
#include <string>
#include <vector>

#include "hylo/clearance.h"
#include "trainer/collocation.hpp"
#include "trainer/corridor.hpp"
#include "trainer/params.hpp"
#include "trainer/switching.hpp"
#include "trainer/terrain_grid.hpp"

namespace hylo::trainer {

struct Waypoint {
	hylo_mode mode = HYLO_MODE_NONE;   // numbered as goal_t MODE_*
	double state[6] = {};          // sampled coordinates (docs/models.md section 7)
	bool guard = false;
	// The smoothed trajectory must pass through this waypoint's position
	// (smoothing_problem cuts its run into two phases there; the via points
	// step of smooth_with_fallbacks sets it). Inner waypoints of a run only.
	bool via = false;
};

// A waypoint's sampled coordinates (as many as its mode samples).
std::vector<double> sampled(const Waypoint &w);

struct SmoothOptions {
	int segments_per_edge = 6;     // collocation segments per plan edge of a phase
	int min_segments = 10, max_segments = 48;
	double guard_half_length_m = 6; // how far a switch point may slide each way (per axis on platforms)
	std::vector<IpoptOption> ipopt_options;  // added to smoothing_solve_options() (hylo-smooth --ipopt-option)
	// Added after ipopt_options to the multi-phase optimization's solves only
	// (fallback steps full, straightened and finer mesh; hylo-smooth
	// --full-ipopt-option): max_iter=1 forces the fallbacks, as a test does.
	std::vector<IpoptOption> full_ipopt_options;
	// Clearance (docs/smoothing.md, "Clearance"): every phase of the ground,
	// marine and flight modes kept in a corridor of boxes whose cells keep
	// the body plus margin_m clear of the mode's hazards (trainer/corridor.hpp).
	bool corridors = true;
	double margin_m = HYLO_DEFAULT_MARGIN_M;
	double corridor_pad_m = 0.02;   // added to the cells' clearance: the cubic between knots may bulge
	bool debug = false;             // a line per Ipopt solve and per replay on stderr (hylo-smooth --debug)
};

// The multi-phase problem of a plan. Throws std::invalid_argument for a plan
// that cannot be smoothed (fewer than two waypoints, a switch without a guard
// pair, a mode of another robot, a switch point off the map).
MultiPhaseProblem smoothing_problem(const RobotParams &robot, const std::vector<Waypoint> &plan,
				    const TerrainGrid &map, const TakeoffLanding &costs,
				    const SmoothOptions &opt = {});

// The plan with each ground or water heading continuing the one before by
// the turn the planner priced (hylo_relative: within pi, a half turn towards
// the goal's side), so that a guess or an edge's solve turns as the plan was
// costed, never the long way round across the wrap at +-pi. The last heading
// is the goal's up to whole turns (the same pose). smoothing_problem applies
// it; so must anything else that solves between a plan's waypoints.
std::vector<Waypoint> unwound_headings(const std::vector<Waypoint> &plan);

// The turn the planner priced from the sampled state tail to head of a
// ground or water mode: their heading change wrapped into (-pi, pi], a half
// turn towards the goal's side (hylo_relative).
double priced_turn(hylo_mode mode, const double *tail, const double *head);

// The plan with every run of one mode straightened: its inner waypoints
// moved onto the line between the run's end points (same count, evenly
// spaced; ground and water headings along the line). Ends, switch points,
// speeds and modes are kept.
std::vector<Waypoint> straightened(const std::vector<Waypoint> &plan);

// The clearance maps of a plan's corridors (body + margin, with and without
// the pad, then the domain alone), or none: opt.corridors off, no map, or a
// map the onboard code refuses (a note in notes says so). Throws
// std::invalid_argument for a margin or pad not finite and >= 0.
std::unique_ptr<CorridorMaps> corridor_maps(const RobotParams &robot, const TerrainGrid &map,
					    const SmoothOptions &opt, std::vector<std::string> &notes);

}  // namespace hylo::trainer

#endif
