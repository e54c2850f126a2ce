#include "trainer/robot_params.hpp"

namespace hylo::trainer {

double ModeParams::at(const std::string &key) const
{
	auto it = values.find(key);
	if (it == values.end())
		throw ParamError("mode " + mode + " has no parameter '" + key + "'");
	return it->second;
}

const ModeParams &RobotParams::mode(const std::string &name) const
{
	auto it = modes.find(name);
	if (it == modes.end())
		throw ParamError(path + ": robot " + robot + " has no mode '" + name + "'");
	return it->second;
}

const ModeParams &RobotParams::mode(hylo_mode id) const
{
	return mode(hylo_mode_str(id));
}

bool RobotParams::has(hylo_mode id) const
{
	return modes.count(hylo_mode_str(id)) != 0;
}

}  // namespace hylo::trainer
