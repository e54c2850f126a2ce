// Export of a fitted SVR as the C header the onboard planner compiles in
// (format: onboard/models/README.md). Deterministic: the same model gives
// the same bytes (no dates; numbers in %.17g, locale-independent).
#ifndef HYLO_TRAINER_SVR_EXPORT_HPP
#define HYLO_TRAINER_SVR_EXPORT_HPP

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hylo/svr.h"
#include "hylo/types.h"

namespace hylo::trainer {

// A named constant written as `#define HYLO_MODEL_<NAME>_<key> value`,
// e.g. the takeoff and landing energies in the Drivocopter flight header.
struct HeaderConstant {
	std::string key;      // upper-case C identifier suffix, e.g. "TAKEOFF_J"
	double value;
	std::string comment;  // one line, units included
};

// A feasibility classifier (libsvm C-SVC, RBF), oriented so that a decision
// value >= 0 means "the trajectory optimization has a solution".
struct ClassifierExport {
	double gamma = 0, rho = 0;
	std::vector<double> sv;         // n_sv * n_features, standardized, row-major
	std::vector<double> coef;       // n_sv
	std::vector<double> feature_offset, feature_scale;
};

// An envelope table (hylo_svr_envelope in onboard/include/hylo/svr.h; the
// trainer computes it in trainer/envelope.cpp): value[((k * n_z + j) * n_v +
// i1) * n_v + i2] bounds the cost of distance cell k, climb cell j, tail
// speed node i1 and head speed node i2 from below.
struct EnvelopeExport {
	uint32_t n_d = 0, n_z = 1, n_v = 0;
	double d_step = 0, z_min = 0, z_step = 0, v_min = 0, v_step = 0;
	std::vector<float> value;       // n_d * n_z * n_v * n_v, each finite and >= 0
};

// Everything the header holds. Field meanings: onboard/include/hylo/svr.h.
struct SvrExport {
	std::string robot;              // lower-case C identifier, e.g. "ambot"
	hylo_mode mode = HYLO_MODE_NONE;   // the header names it twice (its _MODE macro, its name's end)
	int n_features = 0;
	double gamma = 0, rho = 0;
	std::vector<double> sv;         // n_sv * n_features, standardized, row-major
	std::vector<double> coef;       // n_sv
	std::vector<double> feature_offset, feature_scale;  // n_features each
	double label_offset = 0, label_scale = 1;
	bool label_log = false;
	double cost_floor_per_m = 0, cost_floor_j = 0, max_distance_m = 0;
	double speed_min_mps = 0, speed_max_mps = 0;   // both 0: any speed
	// The other coordinates the training draw bounded (hylo_svr_model's
	// state_bounded, state_min, state_max; trained_region, dataset.hpp).
	uint32_t state_bounded = 0;
	std::array<double, 6> state_min{}, state_max{};
	// Provenance lines "key: value", in the order given (sample count, seed,
	// hashes, errors, version). Written into a comment and a string.
	std::vector<std::pair<std::string, std::string>> provenance;
	std::vector<HeaderConstant> constants;
	std::optional<ClassifierExport> feasibility;
	std::optional<EnvelopeExport> envelope;   // ground, marine and flight only
	// Flight only: the turn table (hylo_svr_model.turn_envelope): distance
	// and turn cells over [0, 2 pi], the envelope's distances and speeds.
	std::optional<EnvelopeExport> turn_envelope;
};

// The header text. Throws std::invalid_argument naming the problem (bad
// identifier, size mismatch, non-finite number, no support vectors).
std::string svr_header_text(const SvrExport &m);

// The model a header written by svr_header_text holds, read back so that
// a later stage (the envelope, at export) can work on the fitted model.
// Throws std::invalid_argument naming the problem when text is not such a
// header: it checks that svr_header_text of the result gives text back byte
// for byte, so nothing is lost or changed on the way.
SvrExport parse_svr_header(const std::string &text);

// text, a header this trainer writes (or one of the format before the
// trained region's fields, which it moves to this format), with the cost
// model's state_bounded, state_min and state_max set as given; every other
// byte as it was. Throws std::invalid_argument when the result is not a
// header svr_header_text writes (parse_svr_header's check).
std::string header_with_region(const std::string &text, uint32_t bounded, const std::array<double, 6> &min,
			       const std::array<double, 6> &max);

// Writes svr_header_text(m) to path atomically (temporary file + rename);
// nothing is written when the model is invalid. Throws std::runtime_error
// on I/O errors.
void write_svr_header(const SvrExport &m, const std::string &path);

// The onboard model over m's arrays (Model: SvrExport or ClassifierExport;
// m must outlive it), named name, with n_features features; the other
// fields zero but label_scale 1 (a classifier's decision value, unscaled).
template <class Model>
hylo_svr_model svr_view(const Model &m, int n_features, const char *name)
{
	hylo_svr_model v{};
	v.name = name;
	v.n_sv = static_cast<uint32_t>(m.coef.size());
	v.n_features = static_cast<uint32_t>(n_features);
	v.gamma = m.gamma;
	v.rho = m.rho;
	v.sv = m.sv.data();
	v.coef = m.coef.data();
	v.feature_offset = m.feature_offset.data();
	v.feature_scale = m.feature_scale.data();
	v.label_scale = 1;
	return v;
}

// The onboard cost model over m's arrays (m must outlive it), named name:
// svr_view with m's labels, floors and trained region (no envelope), so
// that hylo_svr_predict gives the cost the header gives.
hylo_svr_model model_view(const SvrExport &m, const char *name);

// Shortest round-trip-exact text of v with 17 significant digits, "%.17g"
// in the C locale.
std::string format_double(double v);

}  // namespace hylo::trainer

#endif
