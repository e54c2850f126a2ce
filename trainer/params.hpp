// Reading robot parameter files (trainer/params/<robot>.yaml; what they hold:
// robot_params.hpp). Strict: an unknown key, a missing key or a bad value is
// an error naming the file, the key and the line.
#ifndef HYLO_TRAINER_PARAMS_HPP
#define HYLO_TRAINER_PARAMS_HPP

#include <string>
#include <utility>
#include <vector>

#include "trainer/robot_params.hpp"

namespace hylo::trainer {

// Loads and validates a robot file. Throws ParamError "FILE:LINE: what".
RobotParams load_robot(const std::string &path);

// The parameter file of robot name: in $HYLO_PARAMS_DIR, else trainer/params/
// of the working directory, else of the checkout the binary was built in,
// else share/hylo/params/ of the prefix it was installed into (make install).
std::string robot_file(const std::string &name);

// The folder robot_file() looks in (without a name to find).
std::string robot_dir();

// The robots of robot_dir(), sorted by name, each with its modes (sorted;
// empty for a file that does not load).
std::vector<std::pair<std::string, std::vector<std::string>>> list_robots();

}  // namespace hylo::trainer

#endif
