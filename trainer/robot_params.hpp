// What a robot file holds (trainer/params/<robot>.yaml, read by params.hpp's
// load_robot): the physical parameters of docs/models.md section 8 per mode,
// the body and the ranges training pairs are drawn from. Types only, so that
// the models (models.hpp) need not see the loader, which asks the models
// for their parameter keys (model_table.hpp).
#ifndef HYLO_TRAINER_ROBOT_PARAMS_HPP
#define HYLO_TRAINER_ROBOT_PARAMS_HPP

#include <map>
#include <stdexcept>
#include <string>

#include "hylo/types.h"

namespace hylo::trainer {

class ParamError : public std::runtime_error {
public:
	using std::runtime_error::runtime_error;
};

struct Sampling {
	double max_distance_m = 0;     // displacement of a training pair, at most
	double speed_min_mps = 0, speed_max_mps = 0;
};

struct ModeParams {
	std::string mode;              // its name (hylo/modes.h), as the file spells it
	hylo_mode id = HYLO_MODE_NONE; // the mode: load() parses the name once
	std::map<std::string, double> values;
	Sampling sampling;
	int refinements = 0;           // solver: {refinements: N}: at least N mesh doublings when a
	                               // replay rejects a solution (stiff modes; 0 = the default)
	// The value of key; throws ParamError if absent (a programming error:
	// load() checks every required key).
	double at(const std::string &key) const;
};

struct RobotParams {
	std::string robot, path;
	double g = 9.81;
	// body: {radius_m: R}: the robot's size, a disc (ground, marine) or a
	// sphere (flight, every attitude) of radius R around its position [m];
	// 0 (no body key): a point. Trajectories keep it clear of what the mode
	// cannot touch (docs/smoothing.md, "Clearance").
	double body_radius_m = 0;
	// SHA-256 of the file without its body block: what every label depends
	// on (the body changes no label, so datasets and models outlive it).
	std::string labels_sha256;
	std::map<std::string, ModeParams> modes;
	const ModeParams &mode(const std::string &name) const;   // throws ParamError
	const ModeParams &mode(hylo_mode id) const;              // likewise
	bool has(hylo_mode id) const;                            // the file has mode id
};

}  // namespace hylo::trainer

#endif
