// Hermite-Simpson direct collocation (free final time) solved with Ipopt, with
// exact sparse first and second derivatives from Eigen's forward-mode
// AutoDiff: single-mode boundary value problems (the training samples) and
// multi-phase problems whose phases, in different modes, are joined at guard
// points by reset maps (the smoother and the fixed-sequence baselines). The
// public entry of the solver driver; its parts (docs/trainer.md, "Solving
// one pair"): the transcription of one phase (hs_phase.hpp), the Ipopt
// adapter (ipopt_nlp), the solve strategy (solve_strategy), the starts
// (starts), each mode's configuration (mode_config), the replay (replay).
#ifndef HYLO_TRAINER_COLLOCATION_HPP
#define HYLO_TRAINER_COLLOCATION_HPP

#include <string>
#include <utility>
#include <vector>

#include "trainer/modes.hpp"
#include "trainer/params.hpp"
#include "trainer/problem.hpp"
#include "trainer/replay.hpp"
#include "trainer/solution.hpp"
#include "trainer/starts.hpp"   // transplanted_guess

namespace hylo::trainer {

// The fields of opt that can change a solve's result, one "name: value" line
// each (newline-terminated): what a dataset's .meta records of the solver.
// Not debug, nor the derivative checker's (a checker run labels nothing),
// nor strategy_starts: only ground and marine have strategies, and their
// datasets' meta says so itself ("starts: 3").
std::string solve_options_text(const SolveOptions &opt);

// Solves the BVP x1s -> x2s (sampled coordinates, the record's xs_dim each) of
// mode with the robot's parameters. Several initial guesses (straight lines
// of three durations; with opt.strategy_starts also solve_bvp_strategies');
// keeps the cheapest converged one whose replay passes, refining the mesh if
// needed.
// Throws std::invalid_argument for an unknown mode or a boundary state
// outside the mode's bounds.
Solution solve_bvp(hylo_mode mode, const RobotParams &robot, const double *x1s,
		   const double *x2s, const SolveOptions &opt);

// The BVP's other initial guesses, where its mode has them (ground and
// marine: through the midpoint backing up, and facing the goal; backing up
// at twice the duration; reversing towards the goal through the midpoint,
// and turning on the spot, reversing, turning on the spot; one duration
// guess each, planar_strategy_guesses in starts.cpp): returns their best if it is cheaper than line, the
// straight-line starts' result (solve_bvp without strategy_starts, or a
// dataset row made by it), else line. Starts, refined starts and seconds
// add up. With opt.refine_within finite, line's cost prunes their
// refinement too.
Solution solve_bvp_strategies(hylo_mode mode, const RobotParams &robot, const double *x1s,
			      const double *x2s, const SolveOptions &opt, const Solution &line);

// The options solve_bvp_guesses solves with: opt without refine_repeats.
SolveOptions guess_solve_options(const SolveOptions &opt);

// Solves the BVP from each guess (as solve_bvp_strategies does its own,
// under guess_solve_options) and
// returns their best if it is cheaper than incumbent, else incumbent; starts,
// refined starts and seconds add up. A guess whose path does not run from
// the BVP's start to its goal (to 1e-9) or whose states are not the record's nx
// long throws std::invalid_argument.
Solution solve_bvp_guesses(hylo_mode mode, const RobotParams &robot, const double *x1s,
			   const double *x2s, const SolveOptions &opt, const std::vector<Guess> &guesses,
			   const Solution &incumbent);

// The full state a mode's sampled coordinates stand for (the virtual
// constraints of docs/models.md section 7).
std::vector<double> full_state(hylo_mode mode, const RobotParams &robot, const double *xs);
// The mode's state bounds (lo, hi), the record's nx each.
std::pair<std::vector<double>, std::vector<double>> state_bounds(hylo_mode mode,
								 const RobotParams &robot);

// Solves a multi-phase problem (problem.hpp) from every start; keeps the cheapest
// converged one whose phases all replay. Throws std::invalid_argument for a
// malformed problem (unknown mode, wrong sizes, a row naming a missing phase).
MultiPhaseSolution solve_multiphase(const RobotParams &robot, const MultiPhaseProblem &problem,
				    const SolveOptions &opt);

}  // namespace hylo::trainer

#endif
