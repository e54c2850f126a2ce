// The modes the trainer knows: each one's record (onboard/include/hylo/modes.h).
// Inside the trainer a mode is a hylo_mode and its record decides what the
// mode is (planar, air, domain, sizes). Names are parsed where they come
// in (parse_mode: the command line; the robot file's reader), goal_t
// numbers cast where plans come in (hylo-smooth's LCM messages, the case
// studies' planner plans), and names printed (hylo_mode_str, mode_name)
// where text goes out. A mode's full
// state and bounds with a robot's parameters are in collocation.hpp, its
// model in model_table.hpp, the solver's per-mode configuration in
// mode_config.hpp.
#ifndef HYLO_TRAINER_MODES_HPP
#define HYLO_TRAINER_MODES_HPP

#include <string>

#include "hylo/modes.h"

namespace hylo::trainer {

// The mode named name: where a mode enters as text (the command line).
// Throws std::invalid_argument naming the known modes for any other name.
hylo_mode parse_mode(const std::string &name);
// The record of mode (inside the trainer modes travel as hylo_mode); throws
// std::invalid_argument for HYLO_MODE_NONE or an invalid value.
const hylo_mode_desc &mode_desc(hylo_mode mode);
// The modes' names, ", "-separated (for messages).
std::string mode_list();

// Whether mode names a mode (the command line's check).
bool known_mode(const std::string &mode);
// The name of a mode as numbered in goal_t (MODE_*) and onboard
// (hylo_mode), for text going out; "" for an unknown one.
std::string mode_name(int goal_mode);

}  // namespace hylo::trainer

#endif
