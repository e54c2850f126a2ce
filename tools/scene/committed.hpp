// What the tools and tests that plan the committed scenes share: the scene
// files (scenes/*.yaml, sorted) and a planner serving every committed robot
// (the models compiled into node/registry), in memory the object owns.
#ifndef HYLO_TOOLS_COMMITTED_HPP
#define HYLO_TOOLS_COMMITTED_HPP

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/planner.h"
#include "node/registry.h"

namespace hylo::scene {

// scenes/*.yaml under the current directory (the repository's root), sorted.
inline std::vector<std::string> committed_scenes()
{
	std::vector<std::string> out;
	for (const auto &e : std::filesystem::directory_iterator("scenes"))
		if (e.path().extension() == ".yaml")
			out.push_back(e.path().string());
	std::sort(out.begin(), out.end());
	return out;
}

class CommittedPlanner {
public:
	// clock: the planner's (hylo_planner_config.clock), or none.
	explicit CommittedPlanner(hylo_clock_fn clock = nullptr)
	{
		hylo_reason r;
		hylo_planner_config cfg{};
		cfg.robots = robots_;
		cfg.n_robots = hylo_registry_robots(robots_, HYLO_MAX_ROBOTS, &r);
		cfg.clock = clock;
		size_ = hylo_planner_size(&cfg);
		mem_.resize(size_ / sizeof(double) + 1);
		pl_ = reinterpret_cast<hylo_planner *>(mem_.data());
		if (hylo_planner_init(pl_, size_, &cfg) != HYLO_OK)
			throw std::runtime_error(std::string("a planner with every committed model: ") +
						 hylo_planner_reason(pl_));
	}
	CommittedPlanner(const CommittedPlanner &) = delete;
	CommittedPlanner &operator=(const CommittedPlanner &) = delete;

	hylo_planner *get() { return pl_; }
	size_t size() const { return size_; }   // hylo_planner_size

private:
	hylo_robot robots_[HYLO_MAX_ROBOTS];
	std::vector<double> mem_;
	hylo_planner *pl_ = nullptr;
	size_t size_ = 0;
};

}  // namespace hylo::scene

#endif
