// Hermite-Simpson direct collocation (free final time) solved with Ipopt, with
// exact sparse first and second derivatives from Eigen's forward-mode
// AutoDiff: single-mode boundary value problems (the training samples) and
// multi-phase problems whose phases, in different modes, are joined at guard
// points by reset maps (the smoother and the fixed-sequence baselines). The
// transcription of one phase is in hs_phase.hpp.
#ifndef HYLO_TRAINER_COLLOCATION_HPP
#define HYLO_TRAINER_COLLOCATION_HPP

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "trainer/params.hpp"
#include "trainer/replay.hpp"

namespace hylo::trainer {

// An Ipopt option for every solve (trainer --ipopt-option NAME=VALUE), set
// after hylo's own settings, so it overrides them.
struct IpoptOption {
	std::string name, value;
};

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
	double objective_scale = 1;       // Ipopt's obj_scaling_factor: on top of the problem's own
					  // objective scaling, 1 / max(1, 10 T_guess) (see smoothing_solve_options)
	// Finite: every start is first solved on the coarse mesh; only starts
	// that reached a solution of their own and whose coarse cost is within
	// this fraction of the best refined result are refined (training data
	// generation, training_solve_options). Infinite: each start is refined.
	// Modes that keep their first accepted start (flight) ignore it.
	double refine_within = std::numeric_limits<double>::infinity();
	// solve_bvp also tries the mode's other initial guesses
	// (solve_bvp_strategies); training_solve_options sets it.
	bool strategy_starts = false;
	bool replay = true;               // check every solution with CVODE
	bool continuation = true;         // smoothed modes: solve with relaxed smoothing first
	std::vector<IpoptOption> ipopt_options;  // set on every solve, in order (parse_ipopt_option)
	bool debug = false;               // a line per Ipopt solve and per replay on stderr
	std::string derivative_test_file; // non-empty: run Ipopt's second-order derivative checker, log here
	double derivative_test_perturbation = 1e-8;  // relative finite-difference step of the checker
};

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

// Why a replayed solution was rejected ("end state: replayed end state off by
// 0.08 (scaled) > tolerance 0.05"), or "replay passed" / "not replayed".
std::string replay_verdict(const Solution &s);

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

// An initial guess of a BVP: the full states it runs through, uniformly in
// time (the first the start, the last the goal), and its duration [s].
struct Guess {
	double T = 0;
	std::vector<std::vector<double>> path;
};

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

// ---- multi-phase problems ------------------------------------------------
// Phases run one after another, each in one mode with its own free duration;
// linear rows tie the last knot of a phase to the first of the next (reset
// maps) and keep switch points on their guards. switching.hpp builds them.

// A safe corridor's piece (trainer/corridor.hpp): over the part [tau0, tau1]
// of a phase's normalized time (0 its start, 1 its end) the position,
// components 0 and 1 (ground, marine) or 0 to 2 (flight), stays in the
// axis-aligned box [lo, hi] (lo and hi of that many components).
struct CorridorBox {
	double tau0 = 0, tau1 = 1;
	std::vector<double> lo, hi;
};

struct PhaseSpec {
	std::string mode;
	int segments = 20;
	double T_guess = 0;                       // [s]; 0: guess path length / typical speed
	std::vector<std::vector<double>> guess;   // full states the initial guess runs through (>= 2)
	// The guess states lie uniformly in time (a solution's knots and
	// midpoints), with a corridor too; else, with one, by arc length.
	bool guess_timed = false;
	// Bounds of the first and last knot's state (state_dim each; empty: the
	// mode's bounds). Equal bounds fix a component.
	std::vector<double> first_lo, first_hi, last_lo, last_hi;
	// Empty: none. Else every knot and midpoint whose normalized time lies in
	// a box's interval is bounded to that box (to the intersection of
	// several); the first and last knots to their own bounds intersected
	// with it (their own alone where that is empty). The initial guess then
	// runs through the guess states at times proportional to arc length.
	std::vector<CorridorBox> corridor;
};

// A state component of a phase's first or last knot.
struct KnotRef {
	int phase = 0;
	bool last = false;
	int component = 0;
};

// lo <= sum coef * component <= hi.
struct LinearRow {
	std::vector<std::pair<KnotRef, double>> terms;
	double lo = 0, hi = 0;
};

struct MultiPhaseProblem {
	std::vector<PhaseSpec> phases;
	std::vector<LinearRow> rows;
	double switch_cost = 0;                      // constant switching costs [J], added to the cost
	std::vector<double> T_scales{1.0, 2.0, 0.5}; // starts: every phase's T_guess times each
	std::vector<std::string> notes;              // passed on to the solution (MultiPhaseSolution::notes)
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
	std::vector<std::string> modes;
	std::vector<Solution> phases;  // per phase: cost, T, trajectory (t from 0), replay
	double solve_seconds = 0;
	// What the problem's builder could not give as asked (the smoother: a
	// corridor piece with less clearance, or none); copied from the problem.
	std::vector<std::string> notes;
};

// Solves a multi-phase problem from every start; keeps the cheapest
// converged one whose phases all replay. Throws std::invalid_argument for a
// malformed problem (unknown mode, wrong sizes, a row naming a missing phase).
MultiPhaseSolution solve_multiphase(const RobotParams &robot, const MultiPhaseProblem &problem,
				    const SolveOptions &opt);

// Re-integrates a solution's control with CVODE (input interpolated as the
// transcription does: linear between knots, through the midpoint); fills
// replay_cost and replay_error. Exposed for tests (a corrupted control).
void replay(const std::string &mode, const RobotParams &robot, Solution &s,
	    double state_tol = kReplayStateTol);

}  // namespace hylo::trainer

#endif
