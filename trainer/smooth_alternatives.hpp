// Choosing a goal's mode sequence by smoothed cost (docs/smoothing.md,
// "Alternatives"): the graph's ranking is only as good as its models, and
// their error differs between mode sequences, so each alternative the
// planner sent is smoothed, within a budget, and the cheapest trajectory
// that passes the exact clearance check wins (the cheapest of all when none
// does: it is then published as not safe).
#ifndef HYLO_TRAINER_SMOOTH_ALTERNATIVES_HPP
#define HYLO_TRAINER_SMOOTH_ALTERNATIVES_HPP

#include <string>
#include <vector>

#include "trainer/clearance.hpp"
#include "trainer/fallbacks.hpp"

namespace hylo::trainer {

// One of a goal's alternatives (plan_alternative_t): the best graph path of
// one mode sequence.
struct PlanAlternative {
	int index = 0;                  // graph rank: 0 is the plan itself, cheapest predicted
	double predicted_j = 0;
	std::vector<Waypoint> plan;
};

// How many alternatives hylo-smooth smooths (--alternatives,
// --alternatives-budget): the first (cheapest predicted) always; each next
// one only while fewer than max_count were smoothed and, with seconds > 0,
// fewer than seconds of wall time have passed since the first began.
struct AlternativesBudget {
	int max_count = 8;
	double seconds = 0;             // 0: no time limit
};

// What became of one alternative.
struct AlternativeOutcome {
	bool smoothed = false;          // false: the budget ran out before it (skipped says which)
	std::string skipped;
	SmoothResult result;            // smoothed: smooth_with_fallbacks of its path
	ClearanceCheck clearance;       // result ok: the exact check of its trajectory
};

struct AlternativesChoice {
	std::vector<AlternativeOutcome> outcomes;   // one per alternative, in the order given
	// The one whose trajectory is cheapest (lowest energy; a tie: the
	// earlier) among those the exact check calls safe, or among every one
	// smoothed when none is; -1: none ok.
	int chosen = -1;
};

// The choice rule above over smoothed outcomes: an index, -1 when none is ok.
int choose_alternative(const std::vector<AlternativeOutcome> &outcomes);

// Smooths the alternatives in the order given (cheapest predicted first),
// each with smooth_with_fallbacks, within the budget, checks each trajectory
// (check_clearance: the robot's body, opt.margin_m) and picks the cheapest
// safe one.
AlternativesChoice smooth_alternatives(const RobotParams &robot, const std::vector<PlanAlternative> &alternatives,
				       const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt,
				       const AlternativesBudget &budget);

}  // namespace hylo::trainer

#endif
