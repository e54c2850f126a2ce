// The solve strategy (internal to the trainer): from each start, a
// continuation over the smoothing on the coarse mesh, then mesh refinement
// until every phase's CVODE replay agrees; starts whose coarse cost cannot
// win are not refined. Problems are stacked phases (hs_phase.hpp) solved by
// the Ipopt adapter (ipopt_nlp.hpp); collocation.cpp builds them.
#ifndef HYLO_TRAINER_SOLVE_STRATEGY_HPP
#define HYLO_TRAINER_SOLVE_STRATEGY_HPP

#include <limits>
#include <string>
#include <vector>

#include "trainer/hs_phase.hpp"
#include "trainer/mode_config.hpp"
#include "trainer/params.hpp"
#include "trainer/problem.hpp"
#include "trainer/solution.hpp"
#include "trainer/starts.hpp"

namespace hylo::trainer::internal {

// One stacked problem as the strategy sees it: modes, their configuration,
// their setups and the rows by knot reference (resolved per mesh, since
// offsets change).
struct Stacked {
	std::vector<hylo_mode> modes;
	std::vector<ModeInfo> info;
	std::vector<PhaseSetup> setups;
	std::vector<LinearRow> rows;
	// The problem's phase each stacked phase is a piece of (hand_overs.hpp;
	// empty: each its own).
	std::vector<size_t> owner;
};

// Solves from each start and keeps the cheapest solution whose replays all
// pass. With opt.refine_within finite, a start is not refined whose coarse
// cost is that fraction above the cheaper of the best refined result and
// incumbent (a cost already known for the problem).
MultiPhaseSolution solve_stacked(const RobotParams &robot, const Stacked &base, const std::vector<Start> &starts,
				 double switch_cost, const SolveOptions &opt,
				 double incumbent = std::numeric_limits<double>::infinity());

}  // namespace hylo::trainer::internal

#endif
