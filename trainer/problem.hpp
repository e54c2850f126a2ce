// What a solve is given beyond its boundary states: initial guesses of a BVP
// (Guess) and multi-phase problems (MultiPhaseProblem: phases, the linear
// rows joining them, corridors). Plain types; collocation.hpp solves them.
#ifndef HYLO_TRAINER_PROBLEM_HPP
#define HYLO_TRAINER_PROBLEM_HPP

#include <string>
#include <utility>
#include <vector>

#include "hylo/types.h"

namespace hylo::trainer {

// An initial guess of a BVP: the full states it runs through, uniformly in
// time (the first the start, the last the goal), and its duration [s].
struct Guess {
	double T = 0;
	std::vector<std::vector<double>> path;
};

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
	hylo_mode mode = HYLO_MODE_NONE;
	int segments = 20;
	double T_guess = 0;                       // [s]; 0: guess path length / typical speed
	std::vector<std::vector<double>> guess;   // full states the initial guess runs through (>= 2)
	// The normalized times of the guess states (increasing, 0 to 1: a
	// solution's knots and midpoints). Empty: with a corridor, proportional
	// to arc length; else uniform.
	std::vector<double> guess_at;
	// Bounds of the first and last knot's state (the record's nx each; empty: the
	// mode's bounds). Equal bounds fix a component.
	std::vector<double> first_lo, first_hi, last_lo, last_hi;
	// Empty: none. Else every knot and midpoint whose normalized time lies in
	// a box's interval is bounded to that box (to the intersection of
	// several); the first and last knots to their own bounds intersected
	// with it (their own alone where that is empty). Where the intervals of
	// consecutive boxes overlap, the phase is solved as pieces, one per box,
	// with a free time for each hand-over (hand_overs.hpp).
	std::vector<CorridorBox> corridor;
	// Every point but the first and last knot kept this far inside each box
	// (in a direction where the boxes it lies in leave room for it): the
	// cubic between two knots on a box's face may cross it by a hair.
	double corridor_inset_m = 0;
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

}  // namespace hylo::trainer

#endif
