// Free hand-overs between corridor boxes (internal to the trainer; docs/
// smoothing.md, "Clearance"). A phase's boxes bound its knots over time
// windows, and consecutive boxes' windows overlap where both hold the path.
// Solved as given, the knot that crosses from one box to the next must do so
// at a time fixed by the guess, and a cheaper path that would cross earlier
// or later is cut off (Table I at 70 m crept towards the optimum a few
// milliseconds per rebuilt corridor). So a phase is solved as pieces, one
// per box, joined with full-state continuity at a knot in both boxes, each
// piece with its own free duration; the pieces' solutions are then joined
// back into the phase's.
#ifndef HYLO_TRAINER_HAND_OVERS_HPP
#define HYLO_TRAINER_HAND_OVERS_HPP

#include <cstddef>
#include <vector>

#include "trainer/hs_phase.hpp"
#include "trainer/mode_config.hpp"
#include "trainer/problem.hpp"
#include "trainer/solution.hpp"

namespace hylo::trainer::internal {

// The phase s (of a mode with info) as its pieces, in time order: one per
// run of boxes between two hand-overs (where the windows of consecutive
// boxes overlap and both pieces it leaves span at least four of the
// phase's segments; the hand-over starts in the middle of the overlap). Each
// piece has the boxes of its run, re-timed to its own normalized time, its
// share of the guess (states at their times), of the duration guess and of
// the segments, and the mode's bounds at its inner ends. A phase without
// such a hand-over (fewer than two boxes, a fixed duration) is one piece,
// itself.
std::vector<PhaseSetup> hand_over_pieces(const PhaseSetup &s, const ModeInfo &info);

// A stacked problem's phases grouped back into the phases they are pieces
// of: owner[k] is the phase piece k belongs to (non-decreasing, from 0).
// A phase's trajectory runs through its pieces' in order (their shared knot
// once), its duration, cost, segments and replay costs add up, its replay
// passed if every piece's did (the worst end-state error, the first failed
// check).
MultiPhaseSolution joined_pieces(MultiPhaseSolution pieces, const std::vector<size_t> &owner);

}  // namespace hylo::trainer::internal

#endif
