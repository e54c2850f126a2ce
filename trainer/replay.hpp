// CVODE replay of a collocation solution: the dynamics integrated under the
// solution's control, interpolated as Hermite-Simpson does (quadratic through
// knot, midpoint and next knot), with the running cost integrated alongside.
#ifndef HYLO_TRAINER_REPLAY_HPP
#define HYLO_TRAINER_REPLAY_HPP

#include <string>

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

}  // namespace hylo::trainer

#endif
