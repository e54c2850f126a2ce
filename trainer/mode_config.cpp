#include "trainer/mode_config.hpp"

#include <stdexcept>
#include <type_traits>

#include "trainer/hs_phase.hpp"
#include "trainer/model_table.hpp"
#include "trainer/modes.hpp"
#include "trainer/starts.hpp"

namespace hylo::trainer::internal {
namespace {

// A phase's initial guesses from M::path_guess, for models that have one.
template <class M, class = void>
struct HasPathGuess : std::false_type {};
template <class M>
struct HasPathGuess<M, std::void_t<decltype(&M::path_guess)>> : std::true_type {};

// What every mode has: sizes, bounds, the transcription of its model, and
// the model's solver hints (models.hpp, SolverHints).
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
	const SolverHints h = M::solver_hints();
	i.position_dims = h.position_dims;
	if (h.mumps_no_permuting_scaling)
		i.mumps_permuting_scaling = 0;
	i.continuation = h.continuation;
	i.min_segments = h.min_segments;
	i.accept_segments = h.accept_segments;
	i.max_step_s = h.max_step_s;
	i.first_accepted = h.first_accepted;
	i.step_max_iter = h.step_max_iter;
	if constexpr (HasPathGuess<M>::value)
		if (h.path_guess_points > 0)
			i.path_guess = [model, k = h.path_guess_points](const std::vector<double> &a,
									 const std::vector<double> &b, double T) {
				return model.path_guess(a, b, T, k);
			};
	return i;
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

// Planar modes (ground, marine): the planar strategy guesses (starts.hpp)
// besides the straight line.
void tune_planar(ModeInfo &i)
{
	i.strategy_guesses = [bd = i.bounds, speed = i.typical_speed, point = PlanarPoint{i.full_state}](
				     const std::vector<double> &a, const std::vector<double> &b) {
		return planar_strategy_guesses(a, b, bd, speed, point);
	};
}

}  // namespace

ModeInfo mode_info(hylo_mode mode, const RobotParams &robot)
{
	const hylo_mode_desc &d = mode_desc(mode);   // throws for an unknown mode
	const ModeParams &p = robot.mode(mode);
	ModeInfo i = with_model(p, robot.g, [](const auto &model) { return info_of(model); });
	i.refinements = p.refinements;
	if (d.planar)
		tune_planar(i);
	return i;
}

}  // namespace hylo::trainer::internal
