// CVODE replay of a collocation solution: the dynamics integrated under the
// solution's control, interpolated as Hermite-Simpson does (quadratic through
// knot, midpoint and next knot), with the running cost integrated alongside.
// Its tolerances and checks are in solution.hpp (ReplayCheck).
#ifndef HYLO_TRAINER_REPLAY_HPP
#define HYLO_TRAINER_REPLAY_HPP

#include <string>

#include "trainer/params.hpp"
#include "trainer/solution.hpp"

namespace hylo::trainer {

// Re-integrates a solution's control with CVODE (input interpolated as the
// transcription does: linear between knots, through the midpoint); fills
// replay_cost and replay_error. Exposed for tests (a corrupted control).
void replay(hylo_mode mode, const RobotParams &robot, Solution &s,
	    double state_tol = kReplayStateTol);

// Why a replayed solution was rejected ("end state: replayed end state off by
// 0.08 (scaled) > tolerance 0.05"), or "replay passed" / "not replayed".
std::string replay_verdict(const Solution &s);

}  // namespace hylo::trainer

#endif
