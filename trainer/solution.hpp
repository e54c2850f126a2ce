// What a solve is asked (SolveOptions, with the Ipopt options it passes on)
// and what it gives back (Solution, MultiPhaseSolution, with the replay check
// they passed or failed): plain types, shared by the transcription
// (hs_phase.hpp), the replay (replay.hpp), the solver driver and its callers
// (collocation.hpp).
#ifndef HYLO_TRAINER_SOLUTION_HPP
#define HYLO_TRAINER_SOLUTION_HPP

#include <limits>
#include <string>
#include <vector>

#include "hylo/types.h"

namespace hylo::trainer {

// Tolerances a replay must meet (docs/models.md section 1): the end state within
// kReplayStateTol of the collocation's, scaled by each state's typical
// magnitude, and the cost within kReplayCostTol relative.
constexpr double kReplayStateTol = 2e-2;
constexpr double kReplayCostTol = 1e-2;

// The replay check a solution failed: "end state" (scaled end-state error),
// "state bounds" (how far, scaled, the replayed states leave the mode's
// bounds), "cost" (relative difference of the replayed cost), "integration"
// (CVODE failed); empty when it passed. The measured value and its tolerance.
struct ReplayCheck {
	std::string check;
	double value = 0, tol = 0;
	int component = -1;   // "state bounds": the state component (docs/models.md order)
	double t_s = 0;       // "state bounds": the knot time where it is worst [s]
};

// An Ipopt option for every solve (trainer --ipopt-option NAME=VALUE), set
// after hylo's own settings, so it overrides them.
struct IpoptOption {
	std::string name, value;
};

// NAME=VALUE as an Ipopt option, checked against Ipopt's registered options
// (the name known, the value of its type and in its range or list). Throws
// std::invalid_argument saying what is wrong. (ipopt_nlp.cpp)
IpoptOption parse_ipopt_option(const std::string &text);

// Fields that can change a result are recorded in a dataset's .meta
// (solve_options_text): a new one must be added there.
struct SolveOptions {
	int segments = 20;
	double tol = 1e-8;
	int max_iter = 1000;
	double T_fixed = 0;               // > 0: T is fixed to this value
	std::vector<double> T_guesses;    // empty: derived from distance and speed
	int refinements = 2;              // mesh doublings of the phases whose replay fails
	double replay_state_tol = kReplayStateTol;  // largest scaled end-state error a replay may show
	double max_step_s = 0;            // > 0: replaces the longest segment of modes that set one
					  // (flight's 20 ms; see smoothing_solve_options)
	int step_max_iter = 0;            // > 0: the iteration limit of every step (cold start,
					  // continuation, refinement) instead of its modes' limits
	int iteration_budget = 0;         // > 0: Ipopt iterations a start may take over all its
					  // steps, each step's limit cut to what is left of it
	double objective_scale = 1;       // Ipopt's obj_scaling_factor: on top of the problem's own
					  // objective scaling, 1 / max(1, 10 T_guess) (see smoothing_solve_options)
	// Finite: every start is first solved on the coarse mesh; only starts
	// that reached a solution of their own and whose coarse cost is within
	// this fraction of the best refined result are refined (`trainer
	// --refine-within`). Infinite (training_solve_options): each start is refined.
	// Modes that keep their first accepted start (flight) ignore it.
	double refine_within = std::numeric_limits<double>::infinity();
	// solve_bvp also tries the mode's other initial guesses
	// (solve_bvp_strategies); training_solve_options sets it.
	bool strategy_starts = false;
	bool replay = true;               // check every solution with CVODE
	bool continuation = true;         // smoothed modes: solve with relaxed smoothing first
	// A ground or marine BVP whose finer mesh fails from the coarse solution
	// solves it again through the continuation's last smoothed level
	// (docs/decisions.md, "A memory of solutions for `--solve`").
	bool refine_retry = true;
	// Each refined start is refined, also one whose coarse optimum (cost
	// and duration to 1e-6) repeats one that an earlier start of the same
	// solve was refined from into an accepted solution: the fine meshes
	// from two such starts can end 0.5-8% apart. Off for the warm starts
	// from stored solutions (guess_solve_options), where most lead back
	// into the label's basin (docs/decisions.md, "Refining only distinct
	// coarse results").
	bool refine_repeats = true;
	std::vector<IpoptOption> ipopt_options;  // set on every solve, in order (parse_ipopt_option)
	bool debug = false;               // a line per Ipopt solve and per replay on stderr
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
	int refined_starts = 0;           // starts taken on to the replay and mesh refinement
	int segments = 0;
	double cost = 0;                  // J [J]
	double T = 0;                     // [s]
	bool replayed = false;
	bool replay_ok = false;
	double replay_cost = 0;           // CVODE replay of the control [J]
	double replay_error = 0;          // largest scaled end-state error of the replay
	ReplayCheck replay_check;         // the check the replay failed (empty: passed)
	double solve_seconds = 0;
	Trajectory traj;
};

struct MultiPhaseSolution {
	bool converged = false;        // Ipopt succeeded and every phase's replay passed
	int status = 0;                // Ipopt's ApplicationReturnStatus of the kept start
	std::string status_text;
	int iterations = 0;
	int starts = 0, converged_starts = 0;
	int refined_starts = 0;        // starts taken on to the replay and mesh refinement
	double cost = 0;               // sum of the phase costs plus switch_cost [J]
	double T = 0;                  // total duration [s]
	double replay_cost = 0;        // sum of the phases' CVODE replay costs plus switch_cost [J]
	double replay_error = 0;       // largest scaled end-state error over the phases
	// Not converged: why the last rejected solution was rejected ("phase 2
	// (ground): end state: ..."); empty when no start converged.
	std::string rejection;
	// The cheapest solution Ipopt reached whose replay failed [J] (infinity: none).
	double rejected_cost = std::numeric_limits<double>::infinity();
	std::vector<hylo_mode> modes;
	std::vector<Solution> phases;  // per phase: cost, T, trajectory (t from 0), replay
	double solve_seconds = 0;
	// What the problem's builder could not give as asked (the smoother: a
	// corridor piece with less clearance, or none); copied from the problem.
	std::vector<std::string> notes;
};

}  // namespace hylo::trainer

#endif
