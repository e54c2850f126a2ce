#include "trainer/mode_config.hpp"

#include <stdexcept>

#include "trainer/hs_phase.hpp"
#include "trainer/modes.hpp"
#include "trainer/starts.hpp"

namespace hylo::trainer::internal {
namespace {

// What every mode has: sizes, bounds, the transcription of its model.
template <class M>
ModeInfo info_of(const M &model)
{
	ModeInfo i;
	i.nx = M::NX;
	i.nu = M::NU;
	i.smoothed = M::kSmoothed;
	i.bounds = model.bounds();
	i.make = [model](double relax, const PhaseSetup &s) -> std::unique_ptr<PhaseBlock> {
		M m = model;
		m.relax = relax;
		return std::make_unique<HsPhase<M>>(m, s);
	};
	i.full_state = [model](const double *xs) {
		auto a = model.full_state(xs);
		return std::vector<double>(a.begin(), a.end());
	};
	i.distance = [model](const double *a, const double *b) { return model.position_distance(a, b); };
	i.typical_speed = model.typical_speed();
	return i;
}

// Flight: segments of at most 20 ms (the rotors' time constant is 13 ms),
// the Hermite guess with fine continuation steps, the first start that
// passes, and no MC64 in MUMPS (2.2x less CPU, same labels); each measured
// in docs/decisions.md, "Flight training: five changes".
void tune_flight(ModeInfo &i, const FlightModel &fm)
{
	i.position_dims = 3;
	i.mumps_permuting_scaling = 0;
	i.continuation = {100.0, 50.0, 30.0, 20.0, 10.0, 5.0, 3.0, 2.0, 1.5, 1.0};
	i.min_segments = 80;
	i.max_step_s = 0.02;
	i.first_accepted = true;
	i.step_max_iter = 400;
	i.path_guess = [fm](const std::vector<double> &a, const std::vector<double> &b, double T) {
		return fm.path_guess(a, b, T, 16);
	};
}

// A sampled planar state (px, py, v, theta) as the mode's full state.
struct PlanarPoint {
	std::function<std::vector<double>(const double *xs)> full_state;
	std::vector<double> operator()(double px, double py, double v, double theta) const
	{
		const double xs[4] = {px, py, v, theta};
		return full_state(xs);
	}
};

// Ground and marine: the planar strategy guesses (starts.hpp) besides the
// straight line.
void tune_planar(ModeInfo &i)
{
	i.position_dims = 2;
	i.strategy_guesses = [bd = i.bounds, speed = i.typical_speed, point = PlanarPoint{i.full_state}](
				     const std::vector<double> &a, const std::vector<double> &b) {
		return planar_strategy_guesses(a, b, bd, speed, point);
	};
}

}  // namespace

ModeInfo mode_info(const std::string &mode, const RobotParams &robot)
{
	if (!known_mode(mode))
		throw std::invalid_argument("unknown mode '" + mode + "' (ground, marine, flight, di_neg, di_pos)");
	const ModeParams &p = robot.mode(mode);
	ModeInfo i = mode == "ground"   ? info_of(GroundModel(p, robot.g))
		     : mode == "marine" ? info_of(MarineModel(p, robot.g))
		     : mode == "flight" ? info_of(FlightModel(p, robot.g))
					: info_of(DiModel(p, mode == "di_pos"));
	i.refinements = p.refinements;
	if (mode == "flight")
		tune_flight(i, FlightModel(p, robot.g));
	if (mode == "ground" || mode == "marine")
		tune_planar(i);
	return i;
}

}  // namespace hylo::trainer::internal
