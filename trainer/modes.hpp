// The modes the trainer knows: names, numbers and sizes (docs/models.md).
// A mode's full state and bounds with a robot's parameters are in
// collocation.hpp, the solver's per-mode configuration in mode_config.hpp.
#ifndef HYLO_TRAINER_MODES_HPP
#define HYLO_TRAINER_MODES_HPP

#include <string>

namespace hylo::trainer {

// Mode names the trainer knows and their sampled dimension (docs/models.md section 7).
bool known_mode(const std::string &mode);
int sampled_dim(const std::string &mode);
// Modes as numbered in goal_t (MODE_*) and onboard (hylo_mode); "" or 0 for
// an unknown one.
std::string mode_name(int goal_mode);
int mode_number(const std::string &mode);

// State and input sizes of a mode.
int state_dim(const std::string &mode);
int input_dim(const std::string &mode);

}  // namespace hylo::trainer

#endif
