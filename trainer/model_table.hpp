// Which trainer model each mode has: one record per mode (the switches
// below), next to the mode's description in onboard/include/hylo/modes.h.
// Everything else the trainer does per mode goes through with_model (an
// instance with the robot's parameters) or with_model_type (the type alone:
// its parameter keys, its sizes), or reads the mode's hylo_mode_desc.
#ifndef HYLO_TRAINER_MODEL_TABLE_HPP
#define HYLO_TRAINER_MODEL_TABLE_HPP

#include <stdexcept>
#include <string>
#include <utility>

#include "hylo/modes.h"
#include "trainer/models.hpp"
#include "trainer/robot_params.hpp"

// A build's extra modes (hylo/types.h): their models, and the cases
// HYLO_EXTRA_MODEL_TYPE_CASES and HYLO_EXTRA_MODEL_CASES of the switches below.
#ifdef HYLO_EXTRA_MODES_H
#define HYLO_EXTRA_MODELS_WANTED   // the models.hpp types are declared
#include HYLO_EXTRA_MODES_H
#endif

namespace hylo::trainer {

template <class M>
struct ModelType {
	using type = M;
};

// f(ModelType<M>{}) for mode's model M. Throws std::invalid_argument for
// HYLO_MODE_NONE or a mode without a model.
template <class F>
decltype(auto) with_model_type(hylo_mode mode, F &&f)
{
	switch (mode) {
	case HYLO_MODE_GROUND:
		return f(ModelType<GroundModel>{});
	case HYLO_MODE_MARINE:
		return f(ModelType<MarineModel>{});
	case HYLO_MODE_FLIGHT:
		return f(ModelType<FlightModel>{});
	case HYLO_MODE_DI_NEG:
	case HYLO_MODE_DI_POS:
		return f(ModelType<DiModel>{});
#ifdef HYLO_EXTRA_MODEL_TYPE_CASES
		HYLO_EXTRA_MODEL_TYPE_CASES
#endif
	default:
		throw std::invalid_argument("no trainer model for mode " + std::to_string(static_cast<int>(mode)));
	}
}

// f(model) for the model of mode p.id with the parameters p (gravity g).
template <class F>
decltype(auto) with_model(const ModeParams &p, double g, F &&f)
{
	switch (p.id) {
	case HYLO_MODE_GROUND:
		return f(GroundModel(p, g));
	case HYLO_MODE_MARINE:
		return f(MarineModel(p, g));
	case HYLO_MODE_FLIGHT:
		return f(FlightModel(p, g));
	case HYLO_MODE_DI_NEG:
	case HYLO_MODE_DI_POS:
		return f(DiModel(p, *hylo_mode_describe(p.id)));
#ifdef HYLO_EXTRA_MODEL_CASES
		HYLO_EXTRA_MODEL_CASES
#endif
	default:
		throw std::invalid_argument("no trainer model for mode '" + p.mode + "'");
	}
}

// Every edge of a model costs at least per_m * its length (hylo_edge_distance)
// + j: it draws at least floor_power() for at least the longer of the
// shortest duration (bounds().T_min) and the length at top_speed().
struct CostFloor {
	double per_m = 0, j = 0;
};

template <class M>
CostFloor cost_floor(const M &model)
{
	return {model.floor_power() / model.top_speed(), model.floor_power() * model.bounds().T_min};
}

}  // namespace hylo::trainer

#endif
