// Final path smoothing (paper section III.A.3; docs/smoothing.md): a plan's
// multi-phase problem solved, from the plan and if that fails from its
// straightened copy. The smoother's files, in the order hylo-smooth uses
// them:
//   smoothing_problem.hpp   the plan's multi-phase problem (phases, corridors, guards)
//   map_guards.hpp          where switch points may slide on the map
//   corridor.hpp            the safe corridors of boxes
//   smoother.hpp            the full optimization (this file)
//   fallbacks.hpp           the fallback chain when it fails
//   domain_check.hpp        whether a trajectory stays in its map's domain
//   smooth_alternatives.hpp choosing among a goal's alternatives by smoothed cost
//   clearance.hpp           the exact clearance check of what is published
#ifndef HYLO_TRAINER_SMOOTHER_HPP
#define HYLO_TRAINER_SMOOTHER_HPP

#include <vector>

#include "trainer/collocation.hpp"
#include "trainer/params.hpp"
#include "trainer/smoothing_problem.hpp"
#include "trainer/switching.hpp"
#include "trainer/terrain_grid.hpp"

namespace hylo::trainer {

// Smooths a plan: the multi-phase problem from the plan itself, and if that
// fails, from its straightened copy (a roadmap's sideways S-curves can stall
// Ipopt; docs/decisions.md, "Smoothing long plans"). The straightened copy
// keeps the plan's own corridors (its straight lines may cross water or
// rock). A converged solution's flight corridors are then rebuilt along it
// and solved again while that saves more than 0.1% (docs/smoothing.md, "Safe
// corridors"). from_straightened (if given) says whether the straightened
// copy's solve was kept.
MultiPhaseSolution smooth_plan(const RobotParams &robot, const std::vector<Waypoint> &plan,
			       const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt,
			       const std::vector<double> &T_scales = {}, bool *from_straightened = nullptr);

// Solver options of the smoother, for plans of tens of metres: a phase's
// replayed end state within 0.05 (scaled; training: 0.02), flight segments
// up to 40 ms (training: 20), up to 1,000 Ipopt iterations per solve, and
// the objective scaled up 100 times (docs/decisions.md, "Smoothing long
// plans").
SolveOptions smoothing_solve_options();

// The same with opt's Ipopt options, and for the chain's first three steps
// (full: full, straightened, finer mesh) opt.full_ipopt_options after them.
SolveOptions smoothing_solve_options(const SmoothOptions &opt, bool full);

}  // namespace hylo::trainer

#endif
