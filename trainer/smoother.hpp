// Final path smoothing (paper section III.A.3): a plan's waypoints are split
// into phases at its guard points, and one multi-phase collocation problem
// with that mode sequence is solved, the switch points free to slide along
// their guards, switching costs included. The smoothed trajectory is the
// optimum from the plan's guess.
//
// The map's domain, with the robot's body and a margin, is enforced along
// each phase by a safe corridor (trainer/corridor.hpp; docs/smoothing.md,
// "Clearance"): axis-aligned boxes of cells that keep body + margin clear of
// the mode's hazards, each bounding the knots of its part of the phase. A
// shore switch point slides on the piece of shore where the ground and the
// water corridors meet (the fitted straight shoreline when they do not); a
// takeoff or landing point on the clear level ground around it. A flight
// crossing a wall (a height step over max_step) is also cut there into two
// phases that meet above the wall's top plus the flight clearance. Where
// the plan itself passes too close for a box, the corridor gives less
// clearance there, or none, and the problem's notes say where. A plan that
// takes off at its first waypoint (lands at its last) starts (ends) with
// the hover above it, no ground phase.
#ifndef HYLO_TRAINER_SMOOTHER_HPP
#define HYLO_TRAINER_SMOOTHER_HPP

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "trainer/collocation.hpp"
#include "trainer/params.hpp"
#include "trainer/switching.hpp"

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

// Flights keep this high above the terrain [m]; the onboard planner's
// HYLO_AIR_CLEARANCE_M (onboard/include/hylo/map.h).
constexpr double kAirClearanceM = 0.5;

struct Waypoint {
	int mode = 0;                  // goal_t MODE_*
	double state[6] = {};          // sampled coordinates (docs/models.md section 7)
	bool guard = false;
	// The smoothed trajectory must pass through this waypoint's position
	// (smoothing_problem cuts its run into two phases there; the via points
	// step of smooth_with_fallbacks sets it). Inner waypoints of a run only.
	bool via = false;
};

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
	double body_radius_m = -1;      // < 0: the robot's (RobotParams::body_radius_m)
	double margin_m = 0.1;          // HYLO_DEFAULT_MARGIN_M
	double corridor_pad_m = 0.02;   // added to the cells' clearance: the cubic between knots may bulge
};

// The multi-phase problem of a plan. Throws std::invalid_argument for a plan
// that cannot be smoothed (fewer than two waypoints, a switch without a guard
// pair, a mode of another robot, a switch point off the map).
MultiPhaseProblem smoothing_problem(const RobotParams &robot, const std::vector<Waypoint> &plan,
				    const TerrainGrid &map, const TakeoffLanding &costs,
				    const SmoothOptions &opt = {});

// The plan with every run of one mode straightened: its inner waypoints
// moved onto the line between the run's end points (same count, evenly
// spaced; ground and water headings along the line). Ends, switch points,
// speeds and modes are kept.
std::vector<Waypoint> straightened(const std::vector<Waypoint> &plan);

// Smooths a plan: the multi-phase problem from the plan itself, and if that
// fails, from its straightened copy (a roadmap's sideways S-curves can stall
// Ipopt; docs/decisions.md, "Smoothing long plans").
// from_straightened (if given) says whether the straightened copy's solve was kept.
MultiPhaseSolution smooth_plan(const RobotParams &robot, const std::vector<Waypoint> &plan,
			       const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt,
			       const std::vector<double> &T_scales = {}, bool *from_straightened = nullptr);

// How far a trajectory leaves its map's domain: for every knot and
// midpoint, a ground (marine) state's distance from the nearest ground
// (water) cell, a flight's depth below the terrain under it; the worst over
// the trajectory. Off the map counts as infinitely far. Modes without a
// terrain class (the double integrator's) are not checked.
struct DomainCheck {
	double worst_m = 0;       // 0: inside everywhere
	int phase = -1;           // where it is worst
	std::string mode;
	double t_s = 0, x_m = 0, y_m = 0;
	double reach_m = 0;       // how far it looks for a cell of the mode's class
	std::string text() const;   // "phase 1 (marine) at t = 3.2 s, (4.1, 7.0) m: 0.9 m from water"
};
DomainCheck domain_check(const MultiPhaseSolution &s, const TerrainGrid &map);

// A trajectory may leave its domain by this much and still be accepted:
// one cell (the switch points sit on cell edges, the map is a raster).
double domain_tolerance_m(const TerrainGrid &map);

// The steps of the fallback chain, numbered as traj_t METHOD_* (docs/smoothing.md).
enum class SmoothMethod { Full = 0, Straightened = 1, FinerMesh = 2, PhaseByPhase = 3, GraphPath = 4, ViaPoints = 5 };
const char *method_name(SmoothMethod m);   // "full", "straightened", "finer mesh", ...

struct SmoothResult {
	bool ok = false;
	SmoothMethod method = SmoothMethod::Full;
	MultiPhaseSolution solution;           // ok: the trajectory (its phases in time order)
	std::vector<std::string> rejections;   // every step that failed, and why ("full: ...")
	std::string failure;                   // !ok: the phase or edge that cannot be followed, and why
	// Cheapest solution of the full problem a step reached that the replay
	// or the domain check rejected [J] (infinity: none).
	double lowest_cost = std::numeric_limits<double>::infinity();
	double seconds = 0;
};

// A trajectory for the plan, from the first step of the chain that gives
// one whose every phase replays:
//   full / straightened  smooth_plan (the plan, then its straightened copy)
//   finer mesh           the plan with twice the segments per edge and four
//                        mesh refinements of the phases whose replay disagrees
//                        (skipped when a full solution replayed but left the
//                        domain)
//   via points           when a full solution left the domain: the full
//                        problem again, made to pass through the plan's
//                        waypoint nearest to where it left, one more waypoint
//                        per solve (up to 8) while it still leaves it
//   phase by phase       each phase solved on its own, the switch states
//                        fixed at the plan's guard points (switch points
//                        pinned, the states the plan has there)
//   graph path           every plan edge solved on its own (the trainer's
//                        single-mode BVP, strategy starts), joined in time
// A step's trajectory is taken if every phase replays (replay_verdict) and it
// stays within domain_tolerance_m of its map's domain (domain_check).
// Not ok only when an edge of the plan itself cannot be solved: failure
// names the edge, its mode and why.
SmoothResult smooth_with_fallbacks(const RobotParams &robot, const std::vector<Waypoint> &plan,
				   const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt);

// One of a goal's alternatives (plan_alternative_t): the best graph path of
// one mode sequence.
struct PlanAlternative {
	int index = 0;                  // graph rank: 0 is the plan itself, cheapest predicted
	double predicted_j = 0;
	std::vector<Waypoint> plan;
};

// How many alternatives hylo-smooth smooths (--alternatives,
// --alternatives-budget): the first (cheapest predicted) always; each next
// one only while fewer than max_count were smoothed and, with seconds > 0,
// fewer than seconds of wall time have passed since the first began.
struct AlternativesBudget {
	int max_count = 8;
	double seconds = 0;             // 0: no time limit
};

// What became of one alternative.
struct AlternativeOutcome {
	bool smoothed = false;          // false: the budget ran out before it (skipped says which)
	std::string skipped;
	SmoothResult result;            // smoothed: smooth_with_fallbacks of its path
};

struct AlternativesChoice {
	std::vector<AlternativeOutcome> outcomes;   // one per alternative, in the order given
	int chosen = -1;   // the one whose trajectory is cheapest (lowest energy; a tie: the earlier); -1: none ok
};

// Smooths the alternatives in the order given (cheapest predicted first),
// each with smooth_with_fallbacks, within the budget, and picks the cheapest
// smoothed trajectory: the graph's ranking is only as good as its models, and
// their error differs between mode sequences (docs/smoothing.md,
// "Alternatives").
AlternativesChoice smooth_alternatives(const RobotParams &robot, const std::vector<PlanAlternative> &alternatives,
				       const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt,
				       const AlternativesBudget &budget);

// The graph path step alone: every edge of the plan solved on its own and
// the solutions joined in time (switches as in smoothing_problem: a guard
// pair adds its switching cost, no phase). Not converged when an edge fails;
// rejection then names it.
MultiPhaseSolution graph_path_trajectory(const RobotParams &robot, const std::vector<Waypoint> &plan,
					 const TakeoffLanding &costs, const SolveOptions &opt);

// Solver options of the smoother, for plans of tens of metres: a phase's
// replayed end state within 0.05 (scaled; training: 0.02), flight segments
// up to 40 ms (training: 20), up to 1,000 Ipopt iterations per solve, and
// the objective scaled up 100 times (docs/decisions.md, "Smoothing long
// plans").
SolveOptions smoothing_solve_options();

// Exact cost of the plan's own path: every edge solved on its own as a
// single-phase problem (opt with the strategy starts too, as the training
// labels), plus the switching costs. Infinity if an edge fails.
double graph_path_cost(const RobotParams &robot, const std::vector<Waypoint> &plan,
		       const TakeoffLanding &costs, const SolveOptions &opt);

}  // namespace hylo::trainer

#endif
