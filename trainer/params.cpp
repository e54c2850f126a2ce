#include "trainer/params.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <dirent.h>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <set>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "hylo/modes.h"
#include "trainer/model_table.hpp"
#include "trainer/modes.hpp"
#include "trainer/sha256.hpp"
#include "trainer/yaml_file.hpp"

namespace hylo::trainer {
namespace {

// Required parameters of a mode (docs/models.md sections 2-5, 8): its model's.
std::vector<std::string> required_keys(hylo_mode mode)
{
	return with_model_type(mode, [](auto t) { return decltype(t)::type::param_keys(); });
}

// The file's text without its top-level body block (the "body:" line and
// the indented or blank lines after it).
std::string without_body(const std::string &path)
{
	std::ifstream f(path, std::ios::binary);
	std::ostringstream ss;
	ss << f.rdbuf();
	const std::string text = ss.str();
	std::string out;
	bool in_body = false;
	for (size_t i = 0; i < text.size();) {
		size_t e = text.find('\n', i);
		e = e == std::string::npos ? text.size() : e + 1;
		const std::string line = text.substr(i, e - i);
		const bool top = !line.empty() && line[0] != ' ' && line[0] != '\t' && line[0] != '\n' && line[0] != '#';
		if (top)
			in_body = line.compare(0, 5, "body:") == 0;
		if (!in_body)
			out += line;
		i = e;
	}
	return out;
}

struct Reader : YamlReader<ParamError> {
	void only(const YAML::Node &n, const std::string &where, const std::set<std::string> &keys) const
	{
		if (!n.IsMap())
			fail(n, where + " must be a mapping");
		for (const auto &kv : n) {
			std::string k = kv.first.as<std::string>();
			if (!keys.count(k))
				fail(kv.first, "unknown key '" + k + "' in " + where);
		}
	}
};

}  // namespace

namespace {

// Where robot files are looked for when the working directory has none: the
// checkout the binary was built in (CHECKOUT/build/bin/trainer), or an
// install (PREFIX/bin/hylo-trainer, PREFIX/share/hylo/params: make install).
std::vector<std::string> other_params_dirs()
{
	char exe[4096];
	ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
	if (n <= 0)
		return {};
	exe[n] = '\0';
	std::string up[3] = {exe, "", ""};   // the binary's folder, its parent, theirs
	up[0] = up[0].substr(0, up[0].rfind('/'));
	up[1] = up[0].substr(0, up[0].rfind('/'));
	up[2] = up[1].substr(0, up[1].rfind('/'));
	return {up[2] + "/trainer/params", up[1] + "/share/hylo/params"};
}

}  // namespace

std::string robot_file(const std::string &name)
{
	const char *dir = std::getenv("HYLO_PARAMS_DIR");
	if (dir && *dir)
		return std::string(dir) + "/" + name + ".yaml";
	std::string here = "trainer/params/" + name + ".yaml";
	if (access(here.c_str(), F_OK) == 0)
		return here;
	for (const std::string &d : other_params_dirs()) {
		std::string there = d + "/" + name + ".yaml";
		if (access(there.c_str(), F_OK) == 0)
			return there;
	}
	return here;
}

std::string robot_dir()
{
	const char *dir = std::getenv("HYLO_PARAMS_DIR");
	if (dir && *dir)
		return dir;
	if (access("trainer/params", F_OK) == 0)
		return "trainer/params";
	for (const std::string &d : other_params_dirs())
		if (access(d.c_str(), F_OK) == 0)
			return d;
	return "trainer/params";
}

std::vector<std::pair<std::string, std::vector<std::string>>> list_robots()
{
	std::vector<std::pair<std::string, std::vector<std::string>>> robots;
	std::string dir = robot_dir();
	DIR *d = opendir(dir.c_str());
	if (!d)
		return robots;
	std::vector<std::string> names;
	while (struct dirent *e = readdir(d)) {
		std::string f = e->d_name;
		if (f.size() > 5 && f.compare(f.size() - 5, 5, ".yaml") == 0 && f[0] != '.')
			names.push_back(f.substr(0, f.size() - 5));
	}
	closedir(d);
	std::sort(names.begin(), names.end());
	for (const std::string &name : names) {
		std::vector<std::string> modes;
		try {
			RobotParams r = load_robot(dir + "/" + name + ".yaml");
			for (const auto &m : r.modes)
				modes.push_back(m.first);
		} catch (const std::exception &) {
			// A file that does not load is listed without modes.
		}
		robots.emplace_back(name, modes);
	}
	return robots;
}

RobotParams load_robot(const std::string &path)
{
	Reader rd{{path}};
	YAML::Node root = load_yaml_mapping<ParamError>(path, "a robot file");
	rd.only(root, "the robot file", {"robot", "g", "body", "modes"});
	RobotParams rp;
	rp.path = path;
	rp.robot = rd.need(root, "robot", "the robot file").as<std::string>();
	rp.g = rd.number(rd.need(root, "g", "the robot file"), "g");
	if (!(rp.g > 0))
		rd.fail(root["g"], "g must be > 0");
	if (YAML::Node b = root["body"]) {
		rd.only(b, "the body", {"radius_m"});
		YAML::Node r = rd.need(b, "radius_m", "the body");
		rp.body_radius_m = rd.number(r, "body.radius_m");
		if (!(rp.body_radius_m >= 0 && rp.body_radius_m < 100))
			rd.fail(r, "body.radius_m must be in [0, 100) m");
	}
	rp.labels_sha256 = sha256_hex(without_body(path));
	YAML::Node modes = rd.need(root, "modes", "the robot file");
	if (!modes.IsMap() || modes.size() == 0)
		rd.fail(modes, "modes must be a non-empty mapping");
	for (const auto &kv : modes) {
		std::string name = kv.first.as<std::string>();
		const hylo_mode id = hylo_mode_parse(name.c_str());
		if (id == HYLO_MODE_NONE)
			rd.fail(kv.first, "unknown mode '" + name + "' (" + mode_list() + ")");
		const std::vector<std::string> req = required_keys(id);
		const YAML::Node &m = kv.second;
		rd.only(m, "mode " + name, {"params", "sampling", "solver"});
		ModeParams mp;
		mp.mode = name;
		mp.id = id;
		YAML::Node p = rd.need(m, "params", "mode " + name);
		std::set<std::string> allowed(req.begin(), req.end());
		rd.only(p, "the parameters of mode " + name, allowed);
		for (const auto &key : req) {
			YAML::Node v = rd.need(p, key, "the parameters of mode " + name);
			double x = rd.number(v, name + "." + key);
			if (!(x > 0))
				rd.fail(v, name + "." + key + " must be > 0, not " + std::to_string(x));
			mp.values[key] = x;
		}
		YAML::Node s = rd.need(m, "sampling", "mode " + name);
		rd.only(s, "the sampling of mode " + name, {"max_distance_m", "speed_min_mps", "speed_max_mps"});
		mp.sampling.max_distance_m = rd.number(rd.need(s, "max_distance_m", "sampling"), "max_distance_m");
		mp.sampling.speed_min_mps = rd.number(rd.need(s, "speed_min_mps", "sampling"), "speed_min_mps");
		mp.sampling.speed_max_mps = rd.number(rd.need(s, "speed_max_mps", "sampling"), "speed_max_mps");
		if (!(mp.sampling.max_distance_m > 0))
			rd.fail(s["max_distance_m"], "max_distance_m must be > 0");
		if (!(mp.sampling.speed_min_mps <= mp.sampling.speed_max_mps))
			rd.fail(s["speed_max_mps"], "speed_max_mps must be >= speed_min_mps");
		if (YAML::Node sv = m["solver"]) {
			rd.only(sv, "the solver settings of mode " + name, {"refinements"});
			YAML::Node r = rd.need(sv, "refinements", "solver");
			double n = rd.number(r, "refinements");
			if (!(n >= 0 && n <= 5 && n == static_cast<int>(n)))
				rd.fail(r, "refinements must be an integer in [0, 5]");
			mp.refinements = static_cast<int>(n);
		}
		rp.modes[name] = mp;
	}
	return rp;
}

}  // namespace hylo::trainer
