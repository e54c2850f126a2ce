// Hermite-Simpson direct collocation of one mode's optimal control problem
// (free final time, fixed boundary states) solved with Ipopt, with exact
// sparse first and second derivatives from Eigen's forward-mode AutoDiff.
//
// Transcription (separated form): N segments, states and inputs at N+1 knots
// and N midpoints, and T. Per segment k, with h = T/N and f_j = f(x_j, u_j):
//   x_m - (x_k + x_k+1)/2 - h/8 (f_k - f_k+1) = 0
//   x_k+1 - x_k - h/6 (f_k + 4 f_m + f_k+1)   = 0
// cost J = h/6 sum_k (L_k + 4 L_m + L_k+1) (Simpson), path constraints at
// every knot and midpoint, bounds on states and inputs everywhere. The input
// is piecewise linear (u_m = (u_k + u_k+1)/2): with free midpoint inputs the
// optimizer chattered and Simpson's rule undercounted the energy by 5-25%
// against the CVODE replay.
#ifndef HYLO_TRAINER_COLLOCATION_HPP
#define HYLO_TRAINER_COLLOCATION_HPP

#include <string>
#include <vector>

#include "trainer/params.hpp"

namespace hylo::trainer {

struct SolveOptions {
	int segments = 20;
	double tol = 1e-8;
	int max_iter = 1000;
	double T_fixed = 0;               // > 0: T is fixed to this value
	std::vector<double> T_guesses;    // empty: derived from distance and speed
	int refinements = 2;              // mesh doublings when the replay rejects a solution
	bool replay = true;               // check every solution with CVODE
	std::string derivative_test_file; // non-empty: run Ipopt's second-order derivative checker, log here
	double derivative_test_perturbation = 1e-8;  // relative finite-difference step of the checker
};

struct Trajectory {
	int nx = 0, nu = 0;
	std::vector<double> t;            // knots and midpoints in time order
	std::vector<double> x, u;         // row-major, one row per time
};

struct Solution {
	bool converged = false;           // Ipopt succeeded (and, if checked, the replay passed)
	int status = 0;                   // Ipopt's ApplicationReturnStatus of the kept start
	std::string status_text;
	int iterations = 0;               // of the kept start
	int starts = 0, converged_starts = 0;
	int segments = 0;
	double cost = 0;                  // J [J]
	double T = 0;                     // [s]
	bool replayed = false;
	bool replay_ok = false;
	double replay_cost = 0;           // CVODE replay of the control [J]
	double replay_error = 0;          // largest scaled end-state error of the replay
	double solve_seconds = 0;
	Trajectory traj;
};

// Mode names the trainer knows and their sampled dimension (models.md section 7).
bool known_mode(const std::string &mode);
int sampled_dim(const std::string &mode);

// Solves the BVP x1s -> x2s (sampled coordinates, sampled_dim(mode) each) of
// mode with the robot's parameters. Several initial guesses; keeps the
// cheapest converged one whose replay passes, refining the mesh if needed.
// Throws std::invalid_argument for an unknown mode or a boundary state
// outside the mode's bounds.
Solution solve_bvp(const std::string &mode, const RobotParams &robot, const double *x1s,
		   const double *x2s, const SolveOptions &opt);

// Re-integrates a solution's control with CVODE (input interpolated as the
// transcription does: linear between knots, through the midpoint); fills
// replay_cost and replay_error. Exposed for tests (a corrupted control).
void replay(const std::string &mode, const RobotParams &robot, Solution &s);

}  // namespace hylo::trainer

#endif
