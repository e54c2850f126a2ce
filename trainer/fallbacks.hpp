// The smoother's fallback chain (docs/smoothing.md, "When the optimization
// fails: the fallback chain"): every plan with status ok gets a trajectory,
// from the first step whose trajectory replays and stays in its domain.
#ifndef HYLO_TRAINER_FALLBACKS_HPP
#define HYLO_TRAINER_FALLBACKS_HPP

#include <limits>
#include <string>
#include <vector>

#include "trainer/collocation.hpp"
#include "trainer/params.hpp"
#include "trainer/smoothing_problem.hpp"
#include "trainer/switching.hpp"
#include "trainer/terrain_grid.hpp"

namespace hylo::trainer {

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
//   graph path           every plan edge solved on its own in its corridor
//                        (else as the trainer's single-mode BVP, strategy
//                        starts), joined in time
// A step's trajectory is taken if every phase replays (replay_verdict) and it
// stays within domain_tolerance_m of its map's domain (domain_check).
// Not ok only when an edge of the plan itself cannot be solved: failure
// names the edge, its mode and why.
SmoothResult smooth_with_fallbacks(const RobotParams &robot, const std::vector<Waypoint> &plan,
				   const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt);

// The graph path step alone: every edge of the plan a phase of its own
// between the plan's states at its ends, in its corridor (opt.corridors:
// the smoothing problem with every waypoint a via point and the switch
// points pinned, each phase solved alone, as phase by phase); where that
// fails, or without corridors, every edge solved on its own as a BVP
// (strategy starts) and the solutions joined in time (a guard pair adds its
// switching cost, no phase). Not converged when an edge fails; rejection
// then names it.
MultiPhaseSolution graph_path_trajectory(const RobotParams &robot, const std::vector<Waypoint> &plan,
					 const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt);

// Exact cost of the plan's own path: every edge solved on its own as a
// single-phase problem (opt with the strategy starts too, as the training
// labels), plus the switching costs. Infinity if an edge fails.
double graph_path_cost(const RobotParams &robot, const std::vector<Waypoint> &plan,
		       const TakeoffLanding &costs, const SolveOptions &opt);

}  // namespace hylo::trainer

#endif
