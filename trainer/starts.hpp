// The starts of a solve (internal to the trainer, but transplanted_guess):
// initial guesses of a BVP and the durations each start is given, all
// inside the mode's duration range [T_min, T_max].
#ifndef HYLO_TRAINER_STARTS_HPP
#define HYLO_TRAINER_STARTS_HPP

#include <functional>
#include <string>
#include <vector>

#include "trainer/models.hpp"
#include "trainer/problem.hpp"
#include "trainer/solution.hpp"

namespace hylo::trainer {

// A solution's path as a guess for another BVP a -> b of its mode (full
// states): its states at `points` (>= 2) uniformly spaced times, each moved
// by (1 - s) (a - x(0)) + s (b - x(T)) at time fraction s, so that the path
// runs from a to b; the solution's duration. The memory-of-motion warm start
// of the repair stage (dataset.hpp, repair).
Guess transplanted_guess(const Trajectory &traj, double T, const std::vector<double> &a,
			 const std::vector<double> &b, int points);

namespace internal {

// A start: every phase's duration guess, and the states phase 0's guess runs
// through (empty: the problem's own).
struct Start {
	std::vector<double> T;
	std::vector<std::vector<double>> path;
};

// The duration guess of a path of the given length at the mode's typical
// speed (not clamped to T_max).
double duration_guess(const Bounds &bd, double typical_speed, double length);

// A BVP's straight-line starts: T_guesses or, empty, the duration guess of
// the distance, twice that, and half that plus T_min.
std::vector<Start> line_starts(const Bounds &bd, const std::vector<double> &T_guesses, double duration);

// Guesses (already checked, check_guesses) as starts of a BVP.
std::vector<Start> guess_starts(const Bounds &bd, const std::vector<Guess> &guesses);

// Throws std::invalid_argument naming the guess unless each runs from a to
// b (to 1e-9) through states of a's size, with a positive finite duration.
void check_guesses(hylo_mode mode, const std::vector<Guess> &guesses, const std::vector<double> &a,
		   const std::vector<double> &b);

// A multi-phase problem's starts: every phase's T_guess times each scale,
// clamped; scales that clamp to the same durations give one start.
std::vector<Start> scaled_starts(const std::vector<Bounds> &bounds, const std::vector<double> &T_guesses,
				 const std::vector<double> &scales);

// Planar modes, x = (px, py, vx, vy, theta, omega, ...): paths a -> b that
// differ in strategy, not only in duration (backing up, facing the goal,
// reversing, turning on the spot; see starts.cpp). point(px, py, v, theta)
// is the mode's full state there.
std::vector<Guess> planar_strategy_guesses(
	const std::vector<double> &a, const std::vector<double> &b, const Bounds &bd, double speed,
	const std::function<std::vector<double>(double, double, double, double)> &point);

}  // namespace internal
}  // namespace hylo::trainer

#endif
