#include "trainer/svr_export.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>

extern "C" {
#include "hylo/features.h"
}

namespace hylo::trainer {
namespace {

struct ModeName {
	const char *name, *c_name;
	hylo_mode value;
};

const ModeName &mode_enum(const std::string &mode)
{
	static const ModeName modes[] = {{"ground", "HYLO_MODE_GROUND", HYLO_MODE_GROUND},
					 {"marine", "HYLO_MODE_MARINE", HYLO_MODE_MARINE},
					 {"flight", "HYLO_MODE_FLIGHT", HYLO_MODE_FLIGHT},
					 {"di_neg", "HYLO_MODE_DI_NEG", HYLO_MODE_DI_NEG},
					 {"di_pos", "HYLO_MODE_DI_POS", HYLO_MODE_DI_POS}};
	for (const ModeName &m : modes)
		if (mode == m.name)
			return m;
	throw std::invalid_argument("svr export: unknown mode '" + mode + "'");
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

void check(const SvrExport &m)
{
	if (!is_identifier(m.robot, false))
		throw std::invalid_argument("svr export: robot name '" + m.robot +
					    "' is not a lower-case C identifier");
	const unsigned nf = hylo_feature_count(mode_enum(m.mode).value);
	if (static_cast<unsigned>(m.n_features) != nf)
		throw std::invalid_argument("svr export: mode " + m.mode + " has " + std::to_string(nf) +
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
	if (!(m.gamma > 0) || !(m.label_scale > 0) || m.cost_floor_per_m < 0 || m.cost_floor_j < 0 ||
	    m.max_distance_m < 0 || m.speed_min_mps > m.speed_max_mps)
		throw std::invalid_argument("svr export: gamma and label_scale must be > 0, "
					    "cost floors and max_distance_m >= 0, "
					    "speed_min_mps <= speed_max_mps");
	for (const auto &c : m.constants) {
		if (!is_identifier(c.key, true))
			throw std::invalid_argument("svr export: constant '" + c.key +
						    "' is not an upper-case C identifier");
		require_finite(c.value, c.key.c_str());
	}
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
	const std::string name = m.robot + "_" + m.mode;
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
	out += "#define " + mac + "_MODE " + mode_enum(m.mode).c_name + "\n";
	out += "#define " + mac + "_N_SV " + std::to_string(m.coef.size()) + "\n";
	out += "#define " + mac + "_N_FEATURES " + std::to_string(m.n_features) + "\n";
	for (const auto &c : m.constants)
		out += "#define " + mac + "_" + c.key + " " + format_double(c.value) + "  /* " +
		       comment_safe(c.comment) + " */\n";
	out += "\n";
	array(out, id + "_sv", mac + "_N_SV * " + mac + "_N_FEATURES", m.sv,
	      static_cast<size_t>(m.n_features));
	array(out, id + "_coef", mac + "_N_SV", m.coef, 4);
	array(out, id + "_feature_offset", mac + "_N_FEATURES", m.feature_offset,
	      static_cast<size_t>(m.n_features));
	array(out, id + "_feature_scale", mac + "_N_FEATURES", m.feature_scale,
	      static_cast<size_t>(m.n_features));
	out += "static const hylo_svr_model " + id + " = {\n";
	out += "\t.name = \"" + name + "\",\n";
	out += "\t.n_sv = " + mac + "_N_SV,\n";
	out += "\t.n_features = " + mac + "_N_FEATURES,\n";
	out += "\t.gamma = " + format_double(m.gamma) + ",\n";
	out += "\t.rho = " + format_double(m.rho) + ",\n";
	out += "\t.sv = " + id + "_sv,\n";
	out += "\t.coef = " + id + "_coef,\n";
	out += "\t.feature_offset = " + id + "_feature_offset,\n";
	out += "\t.feature_scale = " + id + "_feature_scale,\n";
	out += "\t.label_offset = " + format_double(m.label_offset) + ",\n";
	out += "\t.label_scale = " + format_double(m.label_scale) + ",\n";
	out += std::string("\t.label_log = ") + (m.label_log ? "1" : "0") + ",\n";
	out += "\t.cost_floor_per_m = " + format_double(m.cost_floor_per_m) + ",\n";
	out += "\t.cost_floor_j = " + format_double(m.cost_floor_j) + ",\n";
	out += "\t.max_distance_m = " + format_double(m.max_distance_m) + ",\n";
	out += "\t.speed_min_mps = " + format_double(m.speed_min_mps) + ",\n";
	out += "\t.speed_max_mps = " + format_double(m.speed_max_mps) + ",\n";
	out += "\t.provenance = " + c_string(prov) + ",\n";
	out += "};\n\n";
	if (m.feasibility) {
		const ClassifierExport &f = *m.feasibility;
		const std::string fid = id + "_feasibility", fmac = mac + "_FEASIBILITY";
		out += "/* Feasibility classifier: decision >= 0 predicts that the trajectory\n"
		       " * optimization has a solution; the planner drops other edges. */\n";
		out += "#define " + fmac + "_N_SV " + std::to_string(f.coef.size()) + "\n\n";
		array(out, fid + "_sv", fmac + "_N_SV * " + mac + "_N_FEATURES", f.sv,
		      static_cast<size_t>(m.n_features));
		array(out, fid + "_coef", fmac + "_N_SV", f.coef, 4);
		array(out, fid + "_feature_offset", mac + "_N_FEATURES", f.feature_offset,
		      static_cast<size_t>(m.n_features));
		array(out, fid + "_feature_scale", mac + "_N_FEATURES", f.feature_scale,
		      static_cast<size_t>(m.n_features));
		out += "static const hylo_svr_model " + fid + " = {\n";
		out += "\t.name = \"" + name + "_feasibility\",\n";
		out += "\t.n_sv = " + fmac + "_N_SV,\n";
		out += "\t.n_features = " + mac + "_N_FEATURES,\n";
		out += "\t.gamma = " + format_double(f.gamma) + ",\n";
		out += "\t.rho = " + format_double(f.rho) + ",\n";
		out += "\t.sv = " + fid + "_sv,\n";
		out += "\t.coef = " + fid + "_coef,\n";
		out += "\t.feature_offset = " + fid + "_feature_offset,\n";
		out += "\t.feature_scale = " + fid + "_feature_scale,\n";
		out += "\t.label_offset = 0,\n\t.label_scale = 1,\n\t.label_log = 0,\n";
		out += "\t.provenance = " + c_string(prov) + ",\n";
		out += "};\n\n";
	}
	out += "#endif\n";
	return out;
}

void write_svr_header(const SvrExport &m, const std::string &path)
{
	const std::string text = svr_header_text(m);
	const std::string tmp = path + ".tmp";
	{
		std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
		if (!f)
			throw std::runtime_error("cannot write " + tmp);
		f << text;
		f.flush();
		if (!f) {
			std::remove(tmp.c_str());
			throw std::runtime_error("error while writing " + tmp);
		}
	}
	if (std::rename(tmp.c_str(), path.c_str()) != 0) {
		std::remove(tmp.c_str());
		throw std::runtime_error("cannot rename " + tmp + " to " + path);
	}
}

}  // namespace hylo::trainer
