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

}  // namespace

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
			smoothed++;
			const int k = static_cast<int>(c.outcomes.size());
			if (o.result.ok && (c.chosen < 0 ||
					    o.result.solution.cost < c.outcomes[static_cast<size_t>(c.chosen)].result.solution.cost))
				c.chosen = k;
		}
		c.outcomes.push_back(std::move(o));
	}
	return c;
}

}  // namespace hylo::trainer
