// The modes the trainer knows: each one's record (onboard/include/hylo/modes.h)
// by name, for the trainer's edges (command line, robot files, dataset and
// header names). A mode's full state and bounds with a robot's parameters
// are in collocation.hpp, its model in model_table.hpp, the solver's
// per-mode configuration in mode_config.hpp.
#ifndef HYLO_TRAINER_MODES_HPP
#define HYLO_TRAINER_MODES_HPP

#include <string>

#include "hylo/modes.h"

namespace hylo::trainer {

// The mode named name: where a mode enters as text (command line, robot
// and scene files, LCM messages). Throws std::invalid_argument naming the
// known modes for any other name.
hylo_mode parse_mode(const std::string &name);
// The record of mode (inside the trainer modes travel as hylo_mode); throws
// std::invalid_argument for HYLO_MODE_NONE or an invalid value.
const hylo_mode_desc &mode_desc(hylo_mode mode);
// The record of the mode named mode (parse_mode, then its record).
const hylo_mode_desc &mode_desc(const std::string &mode);
// The modes' names, ", "-separated (for messages).
std::string mode_list();

// Mode names the trainer knows and their sampled dimension (docs/models.md section 7).
bool known_mode(const std::string &mode);
int sampled_dim(const std::string &mode);
// Modes as numbered in goal_t (MODE_*) and onboard (hylo_mode); "" or 0 for
// an unknown one.
std::string mode_name(int goal_mode);
int mode_number(const std::string &mode);

// State and input sizes of a mode (0 for an unknown one).
int state_dim(const std::string &mode);
int input_dim(const std::string &mode);

}  // namespace hylo::trainer

#endif
