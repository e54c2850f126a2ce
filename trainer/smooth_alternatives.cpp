#include "trainer/smooth_alternatives.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

namespace hylo::trainer {
namespace {

// Why the budget leaves the next alternative unsmoothed, smoothed having been
// smoothed in elapsed seconds ("": it does not).
std::string over_budget(const AlternativesBudget &budget, int smoothed, double elapsed)
{
	char why[128] = "";
	if (smoothed >= std::max(1, budget.max_count))
		std::snprintf(why, sizeof why, "not smoothed: %d alternative%s smoothed already (the count budget)",
			      smoothed, smoothed == 1 ? "" : "s");
	else if (smoothed > 0 && budget.seconds > 0 && elapsed >= budget.seconds)
		std::snprintf(why, sizeof why, "not smoothed: %.1f s spent already, budget %.4g s", elapsed,
			      budget.seconds);
	return why;
}

// The outcome with the cheapest trajectory (the earlier of equal ones),
// among the safe ones only when safe_only; -1: none.
int cheapest(const std::vector<AlternativeOutcome> &outcomes, bool safe_only)
{
	int best = -1;
	for (size_t k = 0; k < outcomes.size(); k++) {
		const AlternativeOutcome &o = outcomes[k];
		if (!o.result.ok || (safe_only && !o.clearance.safe))
			continue;
		if (best < 0 || o.result.solution.cost < outcomes[static_cast<size_t>(best)].result.solution.cost)
			best = static_cast<int>(k);
	}
	return best;
}

}  // namespace

int choose_alternative(const std::vector<AlternativeOutcome> &outcomes)
{
	const int safe = cheapest(outcomes, true);
	return safe >= 0 ? safe : cheapest(outcomes, false);
}

AlternativesChoice smooth_alternatives(const RobotParams &robot, const std::vector<PlanAlternative> &alternatives,
				       const TerrainGrid &map, const TakeoffLanding &costs, const SmoothOptions &opt,
				       const AlternativesBudget &budget)
{
	AlternativesChoice c;
	const auto t0 = std::chrono::steady_clock::now();
	int smoothed = 0;
	for (const PlanAlternative &a : alternatives) {
		AlternativeOutcome o;
		const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
		o.skipped = over_budget(budget, smoothed, elapsed);
		if (o.skipped.empty()) {
			o.smoothed = true;
			o.result = smooth_with_fallbacks(robot, a.plan, map, costs, opt);
			if (o.result.ok)
				o.clearance = check_clearance(o.result.solution, map, robot.body_radius_m, opt.margin_m);
			smoothed++;
		}
		c.outcomes.push_back(std::move(o));
	}
	c.chosen = choose_alternative(c.outcomes);
	return c;
}

}  // namespace hylo::trainer
