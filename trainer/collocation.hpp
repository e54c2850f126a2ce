// Hermite-Simpson direct collocation (free final time) solved with Ipopt, with
// exact sparse first and second derivatives from Eigen's forward-mode
// AutoDiff: single-mode boundary value problems (the training samples) and
// multi-phase problems whose phases, in different modes, are joined at guard
// points by reset maps (the smoother and the fixed-sequence baselines). The
// transcription of one phase is in hs_phase.hpp.
#ifndef HYLO_TRAINER_COLLOCATION_HPP
#define HYLO_TRAINER_COLLOCATION_HPP

#include <string>
#include <utility>
#include <vector>

#include "trainer/params.hpp"
#include "trainer/problem.hpp"
#include "trainer/replay.hpp"
#include "trainer/solution.hpp"

namespace hylo::trainer {

// NAME=VALUE as an Ipopt option, checked against Ipopt's registered options
// (the name known, the value of its type and in its range or list). Throws
// std::invalid_argument saying what is wrong.
IpoptOption parse_ipopt_option(const std::string &text);

// The fields of opt that can change a solve's result, one "name: value" line
// each (newline-terminated): what a dataset's .meta records of the solver.
// Not debug, nor the derivative checker's (a checker run labels nothing),
// nor strategy_starts: only ground and marine have strategies, and their
// datasets' meta says so itself ("starts: 3").
std::string solve_options_text(const SolveOptions &opt);

// Mode names the trainer knows and their sampled dimension (docs/models.md section 7).
bool known_mode(const std::string &mode);
int sampled_dim(const std::string &mode);
// Modes as numbered in goal_t (MODE_*) and onboard (hylo_mode); "" or 0 for
// an unknown one.
std::string mode_name(int goal_mode);
int mode_number(const std::string &mode);

// Solves the BVP x1s -> x2s (sampled coordinates, sampled_dim(mode) each) of
// mode with the robot's parameters. Several initial guesses (straight lines
// of three durations; with opt.strategy_starts also solve_bvp_strategies');
// keeps the cheapest converged one whose replay passes, refining the mesh if
// needed.
// Throws std::invalid_argument for an unknown mode or a boundary state
// outside the mode's bounds.
Solution solve_bvp(const std::string &mode, const RobotParams &robot, const double *x1s,
		   const double *x2s, const SolveOptions &opt);

// The BVP's other initial guesses, where its mode has them (ground and
// marine: through the midpoint backing up, and facing the goal; backing up
// at twice the duration; reversing towards the goal through the midpoint,
// and turning on the spot, reversing, turning on the spot; one duration
// guess each, planar_strategy_guesses in collocation.cpp): returns their best if it is cheaper than line, the
// straight-line starts' result (solve_bvp without strategy_starts, or a
// dataset row made by it), else line. Starts, refined starts and seconds
// add up. With opt.refine_within finite, line's cost prunes their
// refinement too.
Solution solve_bvp_strategies(const std::string &mode, const RobotParams &robot, const double *x1s,
			      const double *x2s, const SolveOptions &opt, const Solution &line);

// Solves the BVP from each guess (as solve_bvp_strategies does its own) and
// returns their best if it is cheaper than incumbent, else incumbent; starts,
// refined starts and seconds add up. A guess whose path does not run from
// the BVP's start to its goal (to 1e-9) or whose states are not state_dim
// long throws std::invalid_argument.
Solution solve_bvp_guesses(const std::string &mode, const RobotParams &robot, const double *x1s,
			   const double *x2s, const SolveOptions &opt, const std::vector<Guess> &guesses,
			   const Solution &incumbent);

// A solution's path as a guess for another BVP a -> b of its mode (full
// states): its states at `points` (>= 2) uniformly spaced times, each moved
// by (1 - s) (a - x(0)) + s (b - x(T)) at time fraction s, so that the path
// runs from a to b; the solution's duration. The memory-of-motion warm start
// of the repair stage (dataset.hpp, repair).
Guess transplanted_guess(const Trajectory &traj, double T, const std::vector<double> &a,
			 const std::vector<double> &b, int points);

// State and input sizes of a mode, and the full state its sampled
// coordinates stand for (the virtual constraints of docs/models.md section 7).
int state_dim(const std::string &mode);
int input_dim(const std::string &mode);
std::vector<double> full_state(const std::string &mode, const RobotParams &robot, const double *xs);
// The mode's state bounds (lo, hi), state_dim each.
std::pair<std::vector<double>, std::vector<double>> state_bounds(const std::string &mode,
								 const RobotParams &robot);

// Solves a multi-phase problem (problem.hpp) from every start; keeps the cheapest
// converged one whose phases all replay. Throws std::invalid_argument for a
// malformed problem (unknown mode, wrong sizes, a row naming a missing phase).
MultiPhaseSolution solve_multiphase(const RobotParams &robot, const MultiPhaseProblem &problem,
				    const SolveOptions &opt);

}  // namespace hylo::trainer

#endif
