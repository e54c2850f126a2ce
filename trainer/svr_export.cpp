#include "trainer/svr_export.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>
#include <system_error>

#include "hylo/features.h"
#include "hylo/modes.h"
#include "hylo/svr.h"
#include "hylo/types.h"
#include "trainer/files.hpp"

namespace hylo::trainer {
namespace {

// The record of mode (hylo/modes.h: its name and the constant's name,
// c_name, that a header's _MODE macro writes).
const hylo_mode_desc &mode_record(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);
	if (!d)
		throw std::invalid_argument("svr export: unknown mode " + std::to_string(static_cast<int>(mode)));
	return *d;
}

bool is_identifier(const std::string &s, bool upper)
{
	if (s.empty() || (s[0] >= '0' && s[0] <= '9'))
		return false;
	for (char c : s) {
		bool ok = c == '_' || (c >= '0' && c <= '9') ||
			  (upper ? (c >= 'A' && c <= 'Z') : (c >= 'a' && c <= 'z'));
		if (!ok)
			return false;
	}
	return true;
}

std::string upper(std::string s)
{
	for (char &c : s)
		if (c >= 'a' && c <= 'z')
			c = static_cast<char>(c - 'a' + 'A');
	return s;
}

void require_finite(const std::vector<double> &v, const char *what)
{
	for (size_t i = 0; i < v.size(); i++)
		if (!std::isfinite(v[i]))
			throw std::invalid_argument(std::string("svr export: ") + what + "[" +
						    std::to_string(i) + "] is not finite");
}

void require_finite(double v, const char *what)
{
	if (!std::isfinite(v))
		throw std::invalid_argument(std::string("svr export: ") + what + " is not finite");
}

// A C string literal: only printable ASCII; quotes and backslashes escaped.
std::string c_string(const std::string &s)
{
	std::string out = "\"";
	for (char c : s) {
		if (c == '"' || c == '\\')
			out += '\\';
		if (c == '\n')
			out += "\\n";
		else if (c >= 32 && c < 127)
			out += c;
		else
			out += '?';
	}
	return out + "\"";
}

// Comment text: no "*/" may close the comment early.
std::string comment_safe(std::string s)
{
	for (size_t i; (i = s.find("*/")) != std::string::npos;)
		s.replace(i, 2, "* /");
	for (char &c : s)
		if (c == '\n')
			c = ' ';
	return s;
}

void check_arrays(int n_features, const std::vector<double> &sv, const std::vector<double> &coef,
		  const std::vector<double> &offset, const std::vector<double> &scale, double gamma,
		  double rho, const std::string &what)
{
	if (coef.empty())
		throw std::invalid_argument("svr export: the " + what + " has no support vectors");
	if (sv.size() != coef.size() * static_cast<size_t>(n_features))
		throw std::invalid_argument("svr export: " + what + " sv has " + std::to_string(sv.size()) +
					    " values, expected n_sv * n_features = " +
					    std::to_string(coef.size() * n_features));
	if (offset.size() != static_cast<size_t>(n_features) ||
	    scale.size() != static_cast<size_t>(n_features))
		throw std::invalid_argument("svr export: " + what + " feature_offset/scale need n_features values");
	require_finite(sv, "sv");
	require_finite(coef, "coef");
	require_finite(offset, "feature_offset");
	require_finite(scale, "feature_scale");
	for (double s : scale)
		if (!(s > 0))
			throw std::invalid_argument("svr export: a " + what + " feature scale is not > 0");
	require_finite(gamma, "gamma");
	require_finite(rho, "rho");
	if (!(gamma > 0))
		throw std::invalid_argument("svr export: " + what + " gamma must be > 0");
}

// A table's sizes, steps and values (hylo_svr_check's rules); turn: its
// z cells are turns (one cell, or cells covering [0, 2 pi]).
void check_envelope(const EnvelopeExport &e, bool turn, const std::string &what)
{
	if (e.n_d == 0 || e.n_z == 0 || e.n_v == 0)
		throw std::invalid_argument("svr export: envelope cell counts must be >= 1");
	const uint64_t n = static_cast<uint64_t>(e.n_d) * e.n_z * e.n_v * e.n_v;
	if (n >= (uint64_t{1} << 32) || e.value.size() != n)
		throw std::invalid_argument("svr export: envelope has " + std::to_string(e.value.size()) +
					    " values, expected n_d * n_z * n_v * n_v = " + std::to_string(n));
	for (double v : {e.d_step, e.z_min, e.z_step, e.v_min, e.v_step})
		require_finite(v, "an envelope step or origin");
	if (!(e.d_step > 0) || !(e.v_step > 0) || (e.n_z > 1 && !(e.z_step > 0)))
		throw std::invalid_argument("svr export: envelope steps must be > 0");
	const double two_pi = 6.283185307179586476925286766559;
	if (turn && e.n_z > 1 && !(e.z_min == 0 && std::fabs(e.n_z * e.z_step - two_pi) <= 1e-12 * two_pi))
		throw std::invalid_argument("svr export: " + what + " has one climb cell or turn cells "
					    "covering [0, 2 pi] (z_min 0, n_z * z_step = 2 pi)");
	for (size_t i = 0; i < e.value.size(); i++)
		if (!std::isfinite(e.value[i]) || !(e.value[i] >= 0))
			throw std::invalid_argument("svr export: envelope value " + std::to_string(i) +
						    " is not finite and >= 0");
}

void check(const SvrExport &m)
{
	if (!is_identifier(m.robot, false))
		throw std::invalid_argument("svr export: robot name '" + m.robot +
					    "' is not a lower-case C identifier");
	const unsigned nf = hylo_feature_count(mode_record(m.mode).mode);
	if (static_cast<unsigned>(m.n_features) != nf)
		throw std::invalid_argument(std::string("svr export: mode ") + hylo_mode_str(m.mode) + " has " + std::to_string(nf) +
					    " features, the model " + std::to_string(m.n_features));
	check_arrays(m.n_features, m.sv, m.coef, m.feature_offset, m.feature_scale, m.gamma, m.rho,
		     "cost model");
	if (m.feasibility)
		check_arrays(m.n_features, m.feasibility->sv, m.feasibility->coef,
			     m.feasibility->feature_offset, m.feasibility->feature_scale,
			     m.feasibility->gamma, m.feasibility->rho, "feasibility classifier");
	require_finite(m.label_offset, "label_offset");
	require_finite(m.label_scale, "label_scale");
	require_finite(m.cost_floor_per_m, "cost_floor_per_m");
	require_finite(m.cost_floor_j, "cost_floor_j");
	require_finite(m.max_distance_m, "max_distance_m");
	require_finite(m.speed_min_mps, "speed_min_mps");
	require_finite(m.speed_max_mps, "speed_max_mps");
	if (m.state_bounded >> HYLO_XS_DIM)
		throw std::invalid_argument("svr export: state_bounded names a coordinate beyond x^s");
	for (unsigned k = 0; k < HYLO_XS_DIM; k++) {
		require_finite(m.state_min[k], "state_min");
		require_finite(m.state_max[k], "state_max");
		if ((m.state_bounded >> k & 1u) && !(m.state_min[k] <= m.state_max[k]))
			throw std::invalid_argument("svr export: state_min > state_max for coordinate " +
						    std::to_string(k));
	}
	if (!(m.gamma > 0) || !(m.label_scale > 0) || m.cost_floor_per_m < 0 || m.cost_floor_j < 0 ||
	    m.max_distance_m < 0 || m.speed_min_mps > m.speed_max_mps)
		throw std::invalid_argument("svr export: gamma and label_scale must be > 0, "
					    "cost floors and max_distance_m >= 0, "
					    "speed_min_mps <= speed_max_mps");
	if (m.turn_envelope) {
		const hylo_feature_layout *layout = hylo_mode_layout(m.mode);
		const EnvelopeExport &t = *m.turn_envelope;
		if (!layout || layout->kind != HYLO_LAYOUT_SPATIAL || !m.envelope)
			throw std::invalid_argument("svr export: only a flight model with an envelope has a turn table");
		const EnvelopeExport &e = *m.envelope;
		if (t.n_d != e.n_d || t.d_step != e.d_step || t.n_v != e.n_v || t.v_min != e.v_min || t.v_step != e.v_step)
			throw std::invalid_argument("svr export: the turn table's distance cells and speed nodes "
						    "must be the envelope's");
		check_envelope(t, true, "a turn table");
	}
	if (m.envelope) {
		const hylo_feature_layout *layout = hylo_mode_layout(m.mode);
		if (!layout || !layout->envelope)
			throw std::invalid_argument(std::string("svr export: mode ") + hylo_mode_str(m.mode) + " has no envelope");
		check_envelope(*m.envelope, layout->envelope_turn, "a ground or water envelope");
	}
	for (const auto &c : m.constants) {
		if (!is_identifier(c.key, true))
			throw std::invalid_argument("svr export: constant '" + c.key +
						    "' is not an upper-case C identifier");
		require_finite(c.value, c.key.c_str());
	}
}

// A fixed-size field's initializer, "{a, b, ...}".
std::string brace_list(const std::array<double, 6> &v)
{
	std::string out = "{";
	for (size_t k = 0; k < v.size(); k++)
		out += (k ? ", " : "") + format_double(v[k]);
	return out + "}";
}

void array(std::string &out, const std::string &type_name, const std::string &size,
	   const std::vector<double> &v, size_t per_line)
{
	out += "static const double " + type_name + "[" + size + "] = {\n";
	for (size_t i = 0; i < v.size(); i++) {
		out += (i % per_line == 0) ? "\t" : " ";
		out += format_double(v[i]) + ",";
		if (i % per_line == per_line - 1 || i + 1 == v.size())
			out += "\n";
	}
	out += "};\n\n";
}

// The four arrays of one model (Model: SvrExport or ClassifierExport),
// named id + "_sv", "_coef", "_feature_offset", "_feature_scale"; n_sv and
// n_features are the macros sizing them, n the features per row.
template <class Model>
void model_arrays(std::string &out, const Model &f, const std::string &id, const std::string &n_sv,
		  const std::string &n_features, size_t n)
{
	array(out, id + "_sv", n_sv + " * " + n_features, f.sv, n);
	array(out, id + "_coef", n_sv, f.coef, 4);
	array(out, id + "_feature_offset", n_features, f.feature_offset, n);
	array(out, id + "_feature_scale", n_features, f.feature_scale, n);
}

// The hylo_svr_model initializer of m's scalars and the arrays
// model_arrays(out, ..., id, ...) wrote, named name.
void model_struct(std::string &out, const SvrExport &m, const std::string &id, const std::string &name,
		  const std::string &n_sv, const std::string &n_features, const std::string &prov)
{
	// Every field is written, so that C++ (-Wextra: missing initializers)
	// includes the header as cleanly as C.
	const std::pair<const char *, std::string> fields[] = {
		{"name", "\"" + name + "\""},
		{"n_sv", n_sv},
		{"n_features", n_features},
		{"gamma", format_double(m.gamma)},
		{"rho", format_double(m.rho)},
		{"sv", id + "_sv"},
		{"coef", id + "_coef"},
		{"feature_offset", id + "_feature_offset"},
		{"feature_scale", id + "_feature_scale"},
		{"label_offset", format_double(m.label_offset)},
		{"label_scale", format_double(m.label_scale)},
		{"label_log", m.label_log ? "1" : "0"},
		{"cost_floor_per_m", format_double(m.cost_floor_per_m)},
		{"cost_floor_j", format_double(m.cost_floor_j)},
		{"max_distance_m", format_double(m.max_distance_m)},
		{"speed_min_mps", format_double(m.speed_min_mps)},
		{"speed_max_mps", format_double(m.speed_max_mps)},
		{"state_bounded", std::to_string(m.state_bounded)},
		{"state_min", brace_list(m.state_min)},
		{"state_max", brace_list(m.state_max)},
		{"provenance", c_string(prov)},
		{"envelope", m.envelope ? "&" + id + "_envelope" : "NULL"},
		{"turn_envelope", m.turn_envelope ? "&" + id + "_turn_envelope" : "NULL"},
	};
	out += "static const hylo_svr_model " + id + " = {\n";
	for (const auto &f : fields)
		out += std::string("\t.") + f.first + " = " + f.second + ",\n";
	out += "};\n\n";
}

// The float's "%.9g", which a C compiler reads back as the same float (the
// double nearest the text is far closer to the float than to the middle
// between it and a neighbour); checked here.
std::string format_float(float v)
{
	char buf[64];
	auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 9);
	if (r.ec != std::errc())
		throw std::invalid_argument("svr export: cannot format a number");
	double back = 0;
	auto p = std::from_chars(buf, r.ptr, back);
	if (p.ec != std::errc() || static_cast<float>(back) != v)
		throw std::invalid_argument("svr export: a float does not round-trip");
	return std::string(buf, r.ptr);
}

// The table `name` (envelope, turn_envelope) of model id.
void envelope_block(std::string &out, const EnvelopeExport &e, const std::string &id,
		    const std::string &mac, const std::string &name)
{
	const std::string emac = mac + "_" + upper(name);
	if (name == "envelope")
		out += "/* Envelope: per distance (and climb) cell and pair of speed nodes, a lower\n"
		       " * bound of the predicted cost over every heading (onboard/models/README.md). */\n";
	else
		out += "/* Turn table: per distance and turn cell and pair of speed nodes, a lower\n"
		       " * bound of the predicted cost over every climb (onboard/models/README.md). */\n";
	out += "#define " + emac + "_N_D " + std::to_string(e.n_d) + "\n";
	out += "#define " + emac + "_N_Z " + std::to_string(e.n_z) + "\n";
	out += "#define " + emac + "_N_V " + std::to_string(e.n_v) + "\n\n";
	out += "static const float " + id + "_" + name + "_value[" + emac + "_N_D * " + emac + "_N_Z * " +
	       emac + "_N_V * " + emac + "_N_V] = {\n";
	for (size_t i = 0; i < e.value.size(); i++) {
		out += (i % e.n_v == 0) ? "\t" : " ";
		out += format_float(e.value[i]) + ",";
		if (i % e.n_v == e.n_v - 1)
			out += "\n";
	}
	out += "};\n\n";
	out += "static const hylo_svr_envelope " + id + "_" + name + " = {\n";
	out += "\t.n_d = " + emac + "_N_D,\n";
	out += "\t.n_z = " + emac + "_N_Z,\n";
	out += "\t.n_v = " + emac + "_N_V,\n";
	out += "\t.d_step = " + format_double(e.d_step) + ",\n";
	out += "\t.z_min = " + format_double(e.z_min) + ",\n";
	out += "\t.z_step = " + format_double(e.z_step) + ",\n";
	out += "\t.v_min = " + format_double(e.v_min) + ",\n";
	out += "\t.v_step = " + format_double(e.v_step) + ",\n";
	out += "\t.value = " + id + "_" + name + "_value,\n";
	out += "};\n\n";
}

}  // namespace

std::string format_double(double v)
{
	char buf[64];
	auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 17);
	if (r.ec != std::errc())
		throw std::invalid_argument("svr export: cannot format a number");
	return std::string(buf, r.ptr);
}

std::string svr_header_text(const SvrExport &m)
{
	check(m);
	const std::string name = m.robot + "_" + mode_record(m.mode).name;
	const std::string id = "hylo_model_" + name;
	const std::string mac = "HYLO_MODEL_" + upper(name);
	std::string prov;
	for (const auto &p : m.provenance)
		prov += p.first + ": " + p.second + "\n";

	std::string out;
	out += "/*\n * " + name + ": SVR edge-cost model of the hylo onboard planner.\n";
	out += " * Generated by the hylo trainer; do not edit (regenerate with `make models`).\n";
	out += " * Format: onboard/models/README.md.\n *\n";
	for (const auto &p : m.provenance)
		out += " * " + comment_safe(p.first + ": " + p.second) + "\n";
	out += " */\n";
	out += "#ifndef " + mac + "_H\n#define " + mac + "_H\n\n";
	out += "#include \"hylo/svr.h\"\n\n";
	// The format this header is written in; a library that reads another
	// refuses it at compile time (hylo/svr.h, HYLO_MODEL_FORMAT_VERSION).
	const std::string format = std::to_string(HYLO_MODEL_FORMAT_VERSION);
	out += "#define " + mac + "_FORMAT_VERSION " + format + "\n";
	out += "#if HYLO_MODEL_FORMAT_VERSION != " + mac + "_FORMAT_VERSION\n";
	out += "#error \"" + name + ".h is model format " + format +
	       "; this hylo reads another (HYLO_MODEL_FORMAT_VERSION in hylo/svr.h): use a matching hylo or "
	       "regenerate the model\"\n";
	out += "#endif\n";
	out += "#define " + mac + "_MODE " + mode_record(m.mode).c_name + "\n";
	out += "#define " + mac + "_N_SV " + std::to_string(m.coef.size()) + "\n";
	out += "#define " + mac + "_N_FEATURES " + std::to_string(m.n_features) + "\n";
	for (const auto &c : m.constants)
		out += "#define " + mac + "_" + c.key + " " + format_double(c.value) + "  /* " +
		       comment_safe(c.comment) + " */\n";
	out += "\n";
	model_arrays(out, m, id, mac + "_N_SV", mac + "_N_FEATURES", static_cast<size_t>(m.n_features));
	if (m.envelope)
		envelope_block(out, *m.envelope, id, mac, "envelope");
	if (m.turn_envelope)
		envelope_block(out, *m.turn_envelope, id, mac, "turn_envelope");
	model_struct(out, m, id, name, mac + "_N_SV", mac + "_N_FEATURES", prov);
	if (m.feasibility) {
		const ClassifierExport &f = *m.feasibility;
		const std::string fid = id + "_feasibility", fmac = mac + "_FEASIBILITY";
		out += "/* Feasibility classifier: decision >= 0 predicts that the trajectory\n"
		       " * optimization has a solution; the planner drops other edges. */\n";
		out += "#define " + fmac + "_N_SV " + std::to_string(f.coef.size()) + "\n\n";
		model_arrays(out, f, fid, fmac + "_N_SV", mac + "_N_FEATURES", static_cast<size_t>(m.n_features));
		// The classifier's struct: the cost model's fields at their defaults
		// (no label transform, cost floor, trained region or envelope).
		SvrExport fm;
		fm.gamma = f.gamma;
		fm.rho = f.rho;
		model_struct(out, fm, fid, name + "_feasibility", fmac + "_N_SV", mac + "_N_FEATURES", prov);
	}
	out += "#endif\n";
	return out;
}

namespace {

// The pieces of a header svr_header_text wrote, by name.
struct HeaderParts {
	std::vector<std::pair<std::string, std::string>> provenance;
	std::vector<std::pair<std::string, std::string>> defines;   // name, rest of the line
	std::map<std::string, std::vector<std::string>> arrays;     // array name -> number texts
	std::map<std::string, std::map<std::string, std::string>> structs;  // name -> field -> text
	std::vector<std::string> models;   // the hylo_svr_model structs, in order
};

bool starts_with(const std::string &s, const std::string &p) { return s.compare(0, p.size(), p) == 0; }

std::string after(const std::string &s, const std::string &p) { return s.substr(p.size()); }

HeaderParts split_header(const std::string &text)
{
	HeaderParts h;
	std::vector<std::string> lines;
	for (size_t pos = 0; pos < text.size();) {
		size_t end = text.find('\n', pos);
		if (end == std::string::npos)
			throw std::invalid_argument("svr header: the text does not end with a newline");
		lines.push_back(text.substr(pos, end - pos));
		pos = end + 1;
	}
	size_t i = 0;
	while (i < lines.size() && lines[i] != " *")   // the comment's title lines
		i++;
	for (i++; i < lines.size() && lines[i] != " */"; i++) {
		size_t colon = lines[i].find(": ");
		if (!starts_with(lines[i], " * ") || colon == std::string::npos)
			throw std::invalid_argument("svr header: provenance line '" + lines[i] + "' is not ' * key: value'");
		h.provenance.emplace_back(lines[i].substr(3, colon - 3), lines[i].substr(colon + 2));
	}
	for (; i < lines.size(); i++) {
		const std::string &l = lines[i];
		if (starts_with(l, "#define ")) {
			std::string rest = after(l, "#define ");
			size_t sp = rest.find(' ');
			if (sp != std::string::npos)
				h.defines.emplace_back(rest.substr(0, sp), rest.substr(sp + 1));
		} else if (starts_with(l, "static const double ") || starts_with(l, "static const float ")) {
			std::string rest = after(l, starts_with(l, "static const double ") ? "static const double "
										      : "static const float ");
			std::string name = rest.substr(0, rest.find('['));
			std::vector<std::string> &values = h.arrays[name];
			for (i++; i < lines.size() && lines[i] != "};"; i++) {
				std::string item;
				for (char c : lines[i] + ",") {
					if (c == ',') {
						if (!item.empty())
							values.push_back(item);
						item.clear();
					} else if (c != ' ' && c != '\t') {
						item += c;
					}
				}
			}
		} else if (starts_with(l, "static const hylo_svr_model ") ||
			   starts_with(l, "static const hylo_svr_envelope ")) {
			std::string rest = after(l, starts_with(l, "static const hylo_svr_model ")
							    ? "static const hylo_svr_model "
							    : "static const hylo_svr_envelope ");
			const std::string name = rest.substr(0, rest.find(' '));
			if (starts_with(l, "static const hylo_svr_model "))
				h.models.push_back(name);
			std::map<std::string, std::string> &fields = h.structs[name];
			for (i++; i < lines.size() && lines[i] != "};"; i++) {
				size_t eq = lines[i].find(" = ");
				if (!starts_with(lines[i], "\t.") || eq == std::string::npos || lines[i].back() != ',')
					throw std::invalid_argument("svr header: field line '" + lines[i] + "'");
				fields[lines[i].substr(2, eq - 2)] = lines[i].substr(eq + 3, lines[i].size() - eq - 4);
			}
		}
	}
	return h;
}

double number(const std::string &t)
{
	double v = 0;
	auto r = std::from_chars(t.data(), t.data() + t.size(), v);
	if (r.ec != std::errc() || r.ptr != t.data() + t.size())
		throw std::invalid_argument("svr header: '" + t + "' is not a number");
	return v;
}

std::vector<double> numbers(const HeaderParts &h, const std::string &name)
{
	auto it = h.arrays.find(name);
	if (it == h.arrays.end())
		throw std::invalid_argument("svr header: no array " + name);
	std::vector<double> v;
	for (const std::string &t : it->second)
		v.push_back(number(t));
	return v;
}

// The numbers of a brace_list text.
std::array<double, 6> brace_numbers(const std::string &t)
{
	std::array<double, 6> v{};
	if (t.size() < 2 || t.front() != '{' || t.back() != '}')
		throw std::invalid_argument("svr header: '" + t + "' is not a {...} list");
	size_t k = 0, pos = 1;
	while (pos < t.size() - 1) {
		size_t end = t.find(',', pos);
		if (end == std::string::npos)
			end = t.size() - 1;
		if (k == v.size())
			throw std::invalid_argument("svr header: more than 6 numbers in '" + t + "'");
		v[k++] = number(t.substr(pos, end - pos));
		pos = end + 1;
		while (pos < t.size() && t[pos] == ' ')
			pos++;
	}
	if (k != v.size())
		throw std::invalid_argument("svr header: '" + t + "' does not hold 6 numbers");
	return v;
}

const std::map<std::string, std::string> &fields(const HeaderParts &h, const std::string &name)
{
	auto it = h.structs.find(name);
	if (it == h.structs.end())
		throw std::invalid_argument("svr header: no struct " + name);
	return it->second;
}

const std::string &field(const std::map<std::string, std::string> &f, const std::string &key)
{
	auto it = f.find(key);
	if (it == f.end())
		throw std::invalid_argument("svr header: no field ." + key);
	return it->second;
}

// What model_struct and model_arrays wrote of model id (Model: SvrExport or
// ClassifierExport): its gamma, rho and four arrays.
template <class Model>
void read_model(const HeaderParts &h, const std::string &id, Model &m)
{
	const auto &f = fields(h, id);
	m.gamma = number(field(f, "gamma"));
	m.rho = number(field(f, "rho"));
	m.sv = numbers(h, id + "_sv");
	m.coef = numbers(h, id + "_coef");
	m.feature_offset = numbers(h, id + "_feature_offset");
	m.feature_scale = numbers(h, id + "_feature_scale");
}

}  // namespace

SvrExport parse_svr_header(const std::string &text)
{
	const HeaderParts h = split_header(text);
	hylo_mode mode_id = HYLO_MODE_NONE;   // the header's _MODE macro: where its mode comes in
	for (const auto &d : h.defines)
		if (d.first.size() > 5 && d.first.compare(d.first.size() - 5, 5, "_MODE") == 0)
			for (int k = HYLO_MODE_NONE + 1; k < HYLO_MODE_COUNT; k++)
				if (d.second == hylo_mode_describe(static_cast<hylo_mode>(k))->c_name)
					mode_id = static_cast<hylo_mode>(k);
	if (mode_id == HYLO_MODE_NONE)
		throw std::invalid_argument("svr header: no HYLO_MODEL_<NAME>_MODE");
	if (h.models.empty())
		throw std::invalid_argument("svr header: no hylo_svr_model");
	std::string format;
	for (const auto &d : h.defines)
		if (d.first.size() > 15 && d.first.compare(d.first.size() - 15, 15, "_FORMAT_VERSION") == 0)
			format = d.second;
	if (format.empty())
		throw std::invalid_argument("svr header: no HYLO_MODEL_<NAME>_FORMAT_VERSION (written before model "
					    "format versions): fit it again");
	if (format != std::to_string(HYLO_MODEL_FORMAT_VERSION))
		throw std::invalid_argument("svr header: model format " + format + ", but this trainer reads and "
					    "writes format " + std::to_string(HYLO_MODEL_FORMAT_VERSION) +
					    ": fit it again");
	const std::string id = h.models[0];   // the cost model; the classifier follows it
	const auto &f = fields(h, id);
	const std::string &qname = field(f, "name");
	const std::string mode = hylo_mode_str(mode_id);
	SvrExport m;
	const std::string name = qname.size() >= 2 ? qname.substr(1, qname.size() - 2) : "";
	if (name.size() <= mode.size() + 1 || name.compare(name.size() - mode.size() - 1, std::string::npos, "_" + mode) != 0)
		throw std::invalid_argument("svr header: model name '" + name + "' does not end in _" + mode);
	m.robot = name.substr(0, name.size() - mode.size() - 1);
	m.mode = mode_id;
	m.n_features = static_cast<int>(hylo_feature_count(mode_id));
	read_model(h, id, m);
	m.label_offset = number(field(f, "label_offset"));
	m.label_scale = number(field(f, "label_scale"));
	m.label_log = field(f, "label_log") == "1";
	m.cost_floor_per_m = number(field(f, "cost_floor_per_m"));
	m.cost_floor_j = number(field(f, "cost_floor_j"));
	m.max_distance_m = number(field(f, "max_distance_m"));
	m.speed_min_mps = number(field(f, "speed_min_mps"));
	m.speed_max_mps = number(field(f, "speed_max_mps"));
	m.state_bounded = static_cast<uint32_t>(number(field(f, "state_bounded")));
	m.state_min = brace_numbers(field(f, "state_min"));
	m.state_max = brace_numbers(field(f, "state_max"));
	m.provenance = h.provenance;
	const std::string mac = "HYLO_MODEL_" + upper(name) + "_";
	for (const auto &d : h.defines) {
		if (!starts_with(d.first, mac))
			continue;
		std::string key = d.first.substr(mac.size());
		size_t c = d.second.find("  /* ");
		if (key == "MODE" || key == "N_SV" || key == "N_FEATURES" || key == "H" ||
		    starts_with(key, "FEASIBILITY_") || starts_with(key, "ENVELOPE_") || c == std::string::npos ||
		    d.second.size() < c + 8)
			continue;
		m.constants.push_back({key, number(d.second.substr(0, c)),
				       d.second.substr(c + 5, d.second.size() - c - 8)});
	}
	if (h.structs.count(id + "_feasibility")) {
		ClassifierExport c;
		read_model(h, id + "_feasibility", c);
		m.feasibility = c;
	}
	for (const std::string table : {"envelope", "turn_envelope"}) {
		if (!h.structs.count(id + "_" + table))
			continue;
		const auto &ef = fields(h, id + "_" + table);
		EnvelopeExport e;
		const std::string emac = mac + upper(table) + "_";
		auto count = [&](const std::string &key) {
			for (const auto &d : h.defines)
				if (d.first == emac + key)
					return static_cast<uint32_t>(number(d.second));
			throw std::invalid_argument("svr header: no " + emac + key);
		};
		e.n_d = count("N_D");
		e.n_z = count("N_Z");
		e.n_v = count("N_V");
		e.d_step = number(field(ef, "d_step"));
		e.z_min = number(field(ef, "z_min"));
		e.z_step = number(field(ef, "z_step"));
		e.v_min = number(field(ef, "v_min"));
		e.v_step = number(field(ef, "v_step"));
		for (double v : numbers(h, id + "_" + table + "_value"))
			e.value.push_back(static_cast<float>(v));
		(table == "envelope" ? m.envelope : m.turn_envelope) = e;
	}
	std::string again;
	try {
		again = svr_header_text(m);
	} catch (const std::invalid_argument &e) {
		throw std::invalid_argument(std::string("svr header: ") + e.what());
	}
	if (again != text) {
		size_t at = 0, line = 1;
		while (at < again.size() && at < text.size() && again[at] == text[at])
			line += text[at++] == '\n';
		throw std::invalid_argument("svr header: not a header this trainer writes (written again, it "
					    "differs from line " + std::to_string(line) + " on)");
	}
	return m;
}

std::string header_with_region(const std::string &text, uint32_t bounded, const std::array<double, 6> &min,
			       const std::array<double, 6> &max)
{
	const std::string version = std::to_string(HYLO_MODEL_FORMAT_VERSION);
	std::string out;
	int structs = 0;
	for (size_t pos = 0; pos < text.size();) {
		size_t end = text.find('\n', pos);
		if (end == std::string::npos)
			throw std::invalid_argument("svr header: the text does not end with a newline");
		std::string line = text.substr(pos, end - pos);
		pos = end + 1;
		if (starts_with(line, "\t.state_bounded = ") || starts_with(line, "\t.state_min = ") ||
		    starts_with(line, "\t.state_max = "))
			continue;
		size_t at;
		if (starts_with(line, "#define ") && (at = line.rfind("_FORMAT_VERSION ")) != std::string::npos)
			line = line.substr(0, at + 16) + version;
		else if (starts_with(line, "#error \"") && (at = line.find(" is model format ")) != std::string::npos &&
			 line.find(';', at) != std::string::npos)
			line = line.substr(0, at + 17) + version + line.substr(line.find(';', at));
		structs += starts_with(line, "static const hylo_svr_model ");
		out += line + "\n";
		if (starts_with(line, "\t.speed_max_mps = ")) {
			// The cost model's region; the classifier (the second struct) has none.
			const bool cost_model = structs == 1;
			out += "\t.state_bounded = " + std::to_string(cost_model ? bounded : 0) + ",\n";
			out += "\t.state_min = " + brace_list(cost_model ? min : std::array<double, 6>{}) + ",\n";
			out += "\t.state_max = " + brace_list(cost_model ? max : std::array<double, 6>{}) + ",\n";
		}
	}
	SvrExport m = parse_svr_header(out);   // throws unless it is exactly what export writes
	if (m.state_bounded != bounded)
		throw std::invalid_argument("svr header: the region did not land in the cost model");
	return out;
}

void write_svr_header(const SvrExport &m, const std::string &path)
{
	write_file_atomically(path, svr_header_text(m));
}

hylo_svr_model model_view(const SvrExport &m, const char *name)
{
	hylo_svr_model v = svr_view(m, m.n_features, name);
	v.label_offset = m.label_offset;
	v.label_scale = m.label_scale;
	v.label_log = m.label_log ? 1 : 0;
	v.cost_floor_per_m = m.cost_floor_per_m;
	v.cost_floor_j = m.cost_floor_j;
	v.max_distance_m = m.max_distance_m;
	v.speed_min_mps = m.speed_min_mps;
	v.speed_max_mps = m.speed_max_mps;
	v.state_bounded = m.state_bounded;
	for (size_t k = 0; k < m.state_min.size(); k++) {
		v.state_min[k] = m.state_min[k];
		v.state_max[k] = m.state_max[k];
	}
	return v;
}

}  // namespace hylo::trainer
