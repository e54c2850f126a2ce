// CVODE replay of a collocation solution: the dynamics integrated under the
// solution's control, interpolated as Hermite-Simpson does (quadratic through
// knot, midpoint and next knot), with the running cost integrated alongside.
#ifndef HYLO_TRAINER_REPLAY_HPP
#define HYLO_TRAINER_REPLAY_HPP

namespace hylo::trainer {

// Tolerances a replay must meet (docs/models.md section 1): the end state within
// kReplayStateTol of the collocation's, scaled by each state's typical
// magnitude, and the cost within kReplayCostTol relative.
constexpr double kReplayStateTol = 2e-2;
constexpr double kReplayCostTol = 1e-2;

}  // namespace hylo::trainer

#endif
