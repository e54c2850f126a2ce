// The export stage reads the header the fit stage wrote back into the model
// (parse_svr_header, trainer/svr_export.cpp) before it adds the envelope:
// every committed header and small models of each kind (with and without a
// feasibility classifier, constants, an envelope, a flight turn table) come back field for field
// and give the same text again; text this trainer did not write is refused
// with a clear error, and so are envelopes the header cannot hold. Prints
// TAP.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "hylo/features.h"
#include "hylo/svr.h"
#include "tests/tap.hpp"
#include "trainer/svr_export.hpp"

using namespace hylo::trainer;

namespace {

SvrExport small(hylo_mode mode, int nf)
{
	SvrExport m;
	m.robot = "testbot";
	m.mode = mode;
	m.n_features = nf;
	m.gamma = 0.30000000000000004;
	m.rho = -1.25;
	for (int i = 0; i < 3 * nf; i++)
		m.sv.push_back(std::sin(i + 0.5) * 1.7);
	m.coef = {0.1, -2.5, 1e-300};
	for (int k = 0; k < nf; k++) {
		m.feature_offset.push_back(0.1 * k - 0.3);
		m.feature_scale.push_back(1 + 0.01 * k);
	}
	m.label_offset = 3.3;
	m.label_scale = 0.7;
	m.label_log = true;
	m.cost_floor_per_m = 20;
	m.cost_floor_j = 2;
	m.max_distance_m = 4.5;
	m.speed_max_mps = 1.2;
	m.provenance = {{"samples", "3"}, {"note", "a: b, c"}, {"hylo version", "0.1.0"}};
	return m;
}

EnvelopeExport table(uint32_t n_d, uint32_t n_z, uint32_t n_v)
{
	EnvelopeExport e;
	e.n_d = n_d;
	e.n_z = n_z;
	e.n_v = n_v;
	e.d_step = 0.1;
	e.v_step = 0.1;
	if (n_z > 1) {
		e.z_min = -9;
		e.z_step = 0.25;
	}
	for (uint32_t i = 0; i < n_d * n_z * n_v * n_v; i++)
		e.value.push_back(static_cast<float>(10 + i * 0.37 + 1e-7 * i * i));
	return e;
}

bool same(const SvrExport &a, const SvrExport &b)
{
	bool ok = a.robot == b.robot && a.mode == b.mode && a.n_features == b.n_features && a.gamma == b.gamma &&
		  a.rho == b.rho && a.sv == b.sv && a.coef == b.coef && a.feature_offset == b.feature_offset &&
		  a.feature_scale == b.feature_scale && a.label_offset == b.label_offset &&
		  a.label_scale == b.label_scale && a.label_log == b.label_log &&
		  a.cost_floor_per_m == b.cost_floor_per_m && a.cost_floor_j == b.cost_floor_j &&
		  a.max_distance_m == b.max_distance_m && a.speed_min_mps == b.speed_min_mps &&
		  a.speed_max_mps == b.speed_max_mps && a.state_bounded == b.state_bounded &&
		  a.state_min == b.state_min && a.state_max == b.state_max && a.provenance == b.provenance &&
		  a.constants.size() == b.constants.size() && a.feasibility.has_value() == b.feasibility.has_value() &&
		  a.envelope.has_value() == b.envelope.has_value() &&
		  a.turn_envelope.has_value() == b.turn_envelope.has_value();
	for (size_t i = 0; ok && i < a.constants.size(); i++)
		ok = a.constants[i].key == b.constants[i].key && a.constants[i].value == b.constants[i].value &&
		     a.constants[i].comment == b.constants[i].comment;
	if (ok && a.feasibility)
		ok = a.feasibility->sv == b.feasibility->sv && a.feasibility->coef == b.feasibility->coef &&
		     a.feasibility->rho == b.feasibility->rho && a.feasibility->gamma == b.feasibility->gamma;
	for (std::optional<EnvelopeExport> SvrExport::*t : {&SvrExport::envelope, &SvrExport::turn_envelope}) {
		if (!ok || !(a.*t))
			continue;
		const EnvelopeExport &x = *(a.*t), &y = *(b.*t);
		ok = x.n_d == y.n_d && x.n_z == y.n_z && x.n_v == y.n_v && x.d_step == y.d_step &&
		     x.z_min == y.z_min && x.z_step == y.z_step && x.v_min == y.v_min && x.v_step == y.v_step &&
		     x.value == y.value;
	}
	return ok;
}

void round_trip(const SvrExport &m, const std::string &name)
{
	std::string text = svr_header_text(m);
	try {
		SvrExport back = parse_svr_header(text);
		check(same(back, m) && svr_header_text(back) == text, name);
	} catch (const std::exception &e) {
		check(false, name, e.what());
	}
}

}  // namespace

int main()
{
	SvrExport ground = small(HYLO_MODE_GROUND, 8);
	round_trip(ground, "a ground model comes back field for field");
	ground.envelope = table(3, 1, 2);
	ground.provenance.insert(ground.provenance.end() - 1, {"envelope", "3 x 1 x 2 cells, margin 0.001"});
	ClassifierExport c;
	c.gamma = 0.5;
	c.rho = 0.25;
	c.sv = ground.sv;
	c.coef = {1, -1, 0.5};
	c.feature_offset = ground.feature_offset;
	c.feature_scale = ground.feature_scale;
	ground.feasibility = c;
	round_trip(ground, "with its envelope and feasibility classifier too");
	SvrExport turning = ground;
	turning.envelope = table(3, 16, 2);
	turning.envelope->z_min = 0;
	turning.envelope->z_step = 2 * 3.14159265358979323846 / 16;
	round_trip(turning, "with an envelope of 16 turn cells over [0, 2 pi]");
	SvrExport flight = small(HYLO_MODE_FLIGHT, 9);
	flight.constants = {{"TAKEOFF_J", 375.33, "ground rest -> hover 1 m above [J]"},
			    {"LANDING_J", 385.6, "hover 1 m above -> ground rest [J]"}};
	flight.envelope = table(2, 3, 3);
	round_trip(flight, "a flight model with constants and climb cells");
	flight.state_bounded = 7u << 3;
	flight.state_min = {0, 0, 0, -8, -8, -0.25};
	flight.state_max = {0, 0, 0, 8, 8, 1e-300};
	round_trip(flight, "with its trained region (vx, vy, vz bounded)");
	flight.turn_envelope = table(2, 16, 3);
	flight.turn_envelope->z_min = 0;
	flight.turn_envelope->z_step = 2 * 3.14159265358979323846 / 16;
	flight.turn_envelope->d_step = flight.envelope->d_step;
	flight.turn_envelope->v_min = flight.envelope->v_min;
	flight.turn_envelope->v_step = flight.envelope->v_step;
	round_trip(flight, "with a turn table of 16 turn cells over [0, 2 pi]");
	SvrExport di = small(HYLO_MODE_DI_NEG, HYLO_FEATURES_DI);
	di.robot = "di";
	round_trip(di, "a double-integrator model (whose name repeats its mode's prefix)");

	size_t headers = 0, parsed = 0;
	for (const auto &f : std::filesystem::directory_iterator("onboard/models")) {
		if (f.path().extension() != ".h")
			continue;
		std::ifstream in(f.path(), std::ios::binary);
		std::stringstream ss;
		ss << in.rdbuf();
		headers++;
		try {
			SvrExport m = parse_svr_header(ss.str());
			parsed += svr_header_text(m) == ss.str();
		} catch (const std::exception &e) {
			std::printf("# %s: %s\n", f.path().c_str(), e.what());
		}
	}
	check(headers >= 6 && parsed == headers, "every committed header parses and is written again unchanged",
	      std::to_string(parsed) + " of " + std::to_string(headers));

	// The region stage's edit: the region set, nothing else changed; a
	// header of the format before the region's fields (no such lines,
	// format one less) comes out as this trainer writes it.
	{
		SvrExport plain = flight;
		ClassifierExport fc = c;   // the classifier's struct gets no region
		fc.sv = flight.sv;
		fc.feature_offset = flight.feature_offset;
		fc.feature_scale = flight.feature_scale;
		plain.feasibility = fc;
		plain.state_bounded = 0;
		plain.state_min = plain.state_max = {};
		const std::string before = svr_header_text(plain), after = svr_header_text([&] {
			SvrExport m = plain;
			m.state_bounded = 1u << 5;
			m.state_max[5] = 0.5;
			return m;
		}());
		std::array<double, 6> lo{}, hi{};
		hi[5] = 0.5;
		check(header_with_region(before, 1u << 5, lo, hi) == after,
		      "header_with_region sets the cost model's region and changes nothing else");
		std::string old_format;
		const std::string v = std::to_string(HYLO_MODEL_FORMAT_VERSION), v0 = std::to_string(HYLO_MODEL_FORMAT_VERSION - 1);
		std::istringstream lines(before);
		for (std::string l; std::getline(lines, l);) {
			if (l.rfind("\t.state_", 0) == 0)
				continue;
			if (l.rfind("#define HYLO_MODEL_TESTBOT_FLIGHT_FORMAT_VERSION ", 0) == 0)
				l = "#define HYLO_MODEL_TESTBOT_FLIGHT_FORMAT_VERSION " + v0;
			else if (l.find("is model format " + v + ";") != std::string::npos)
				l.replace(l.find("is model format " + v + ";"), 17 + v.size(), "is model format " + v0 + ";");
			old_format += l + "\n";
		}
		check(old_format != before && header_with_region(old_format, 1u << 5, lo, hi) == after,
		      "header_with_region moves a header of the format before the region to this one");
		check_throws([&] { header_with_region(before.substr(0, before.size() - 1), 0, lo, hi); }, "newline",
			     "header_with_region refuses what is not a header");
		std::array<double, 6> inverted = hi;
		inverted[5] = -1;
		check_throws([&] { header_with_region(before, 1u << 5, lo, inverted); }, "state_min > state_max",
			     "header_with_region refuses an empty range");
	}

	std::string text = svr_header_text(flight);
	std::string edited = text;
	edited.replace(edited.find(".rho = -1.25"), 12, ".rho = -1.250");
	check_throws([&] { parse_svr_header(edited); }, "not a header this trainer writes",
		     "a number written differently: refused, naming where");
	edited = text;
	edited.replace(edited.find("static const hylo_svr_model hylo_model_testbot_flight = {"), 6, "const ");
	check_throws([&] { parse_svr_header(edited); }, "svr header", "the model's struct missing: refused");
	check_throws([&] { parse_svr_header(text.substr(0, text.size() - 1)); }, "newline",
		     "a truncated header: refused");
	const std::string format_line = "#define HYLO_MODEL_TESTBOT_FLIGHT_FORMAT_VERSION " +
					std::to_string(HYLO_MODEL_FORMAT_VERSION) + "\n";
	check(text.find(format_line) != std::string::npos,
	      "the header states its format, HYLO_MODEL_FORMAT_VERSION of hylo/svr.h");
	edited = text;
	edited.replace(edited.find(format_line), format_line.size(), "");
	check_throws([&] { parse_svr_header(edited); }, "before model format versions",
		     "a header without a format version: refused");
	edited = text;
	edited.replace(edited.find(format_line), format_line.size(),
		       "#define HYLO_MODEL_TESTBOT_FLIGHT_FORMAT_VERSION " +
			       std::to_string(HYLO_MODEL_FORMAT_VERSION + 1) + "\n");
	check_throws([&] { parse_svr_header(edited); }, "model format " + std::to_string(HYLO_MODEL_FORMAT_VERSION + 1),
		     "a header of another format: refused, naming both");
	SvrExport bad = flight;
	bad.envelope->value.pop_back();
	check_throws([&] { svr_header_text(bad); }, "envelope has", "an envelope of the wrong size: refused");
	bad = flight;
	bad.envelope->value[4] = -1;
	check_throws([&] { svr_header_text(bad); }, "envelope value 4", "a negative envelope value: refused");
	bad = flight;
	bad.envelope->z_step = 0;
	check_throws([&] { svr_header_text(bad); }, "steps", "climb cells without a climb step: refused");
	bad = ground;
	bad.envelope = table(2, 3, 3);
	check_throws([&] { svr_header_text(bad); }, "climb cell",
		     "climb cells on a ground model (not turn cells over [0, 2 pi]): refused");
	bad = turning;
	bad.envelope->z_step *= 1 + 1e-9;
	check_throws([&] { svr_header_text(bad); }, "turn cells covering [0, 2 pi]",
		     "turn cells that do not cover [0, 2 pi]: refused");
	bad = flight;
	bad.turn_envelope->v_step *= 2;
	check_throws([&] { svr_header_text(bad); }, "distance cells and speed nodes",
		     "a turn table with other speed nodes than the envelope's: refused");
	bad = flight;
	bad.turn_envelope->n_z = 8;
	bad.turn_envelope->value.resize(2 * 8 * 9);
	check_throws([&] { svr_header_text(bad); }, "turn cells covering [0, 2 pi]",
		     "a turn table whose turn cells do not cover [0, 2 pi]: refused");
	bad = turning;
	bad.turn_envelope = table(3, 16, 2);
	check_throws([&] { svr_header_text(bad); }, "only a flight model",
		     "a turn table on a ground model: refused");
	bad = di;
	bad.envelope = table(2, 1, 3);
	check_throws([&] { svr_header_text(bad); }, "no envelope", "an envelope on a double integrator: refused");
	return tap_finish();
}
