// What the solver driver needs of each mode (internal to the trainer): its
// sizes, bounds and dynamics as a transcription phase, and its tuning (the
// continuation steps, mesh, iteration limits, MUMPS setting, initial
// guesses). mode_info() in mode_config.cpp builds it from the mode's model
// (trainer/model_table.hpp), whose solver_hints() are the tuning
// (trainer/models.hpp), and the mode's record (hylo/modes.h: planar modes
// get the planar strategy guesses).
#ifndef HYLO_TRAINER_MODE_CONFIG_HPP
#define HYLO_TRAINER_MODE_CONFIG_HPP

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "trainer/ipopt_nlp.hpp"
#include "trainer/models.hpp"
#include "trainer/params.hpp"
#include "trainer/problem.hpp"

namespace hylo::trainer::internal {

struct ModeInfo {
	int nx = 0, nu = 0;
	bool smoothed = false;
	Bounds bounds;
	int position_dims = 0;        // position components a corridor box bounds (0: none)
	std::function<std::unique_ptr<PhaseBlock>(double relax, const PhaseSetup &)> make;
	std::function<std::vector<double>(const double *xs)> full_state;
	std::function<double(const double *a, const double *b)> distance;   // between full states
	double typical_speed = 1;
	std::vector<double> continuation = {100.0, 10.0, 3.0, 1.0};  // smoothing multipliers, to 1
	int refinements = 0;          // the parameter file's solver: {refinements: N}
	int min_segments = 0;         // a start's mesh has at least these segments
	int accept_segments = 0;      // > 0: a BVP's solution is accepted on at least these
	double max_step_s = 0;        // > 0: and segments of at most this guessed duration [s]
	bool first_accepted = false;  // keep the first start that passes, try no more
	int step_max_iter = 0;        // > 0: a continuation step's iteration limit; a start
				      // whose step fails is given up
	int mumps_permuting_scaling = kMumpsChoosesPermutingScaling;
	// Set: the initial guess of a phase guessed as a straight line a -> b,
	// given its duration T (the start's).
	std::function<std::vector<std::vector<double>>(const std::vector<double> &a,
						       const std::vector<double> &b, double T)> path_guess;
	// Set: the initial guesses of a BVP a -> b besides the straight line
	// (solve_bvp_strategies).
	std::function<std::vector<Guess>(const std::vector<double> &a, const std::vector<double> &b)> strategy_guesses;
};

// The mode's ModeInfo with the robot's parameters. Throws
// std::invalid_argument for an unknown mode.
ModeInfo mode_info(hylo_mode mode, const RobotParams &robot);

}  // namespace hylo::trainer::internal

#endif
