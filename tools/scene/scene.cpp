#include "tools/scene/scene.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "hylo/modes.h"
#include "trainer/yaml_file.hpp"

namespace hylo::scene {
namespace {

constexpr int8_t kObstacle = 0, kGround = 1, kWater = 2;

struct Ctx : trainer::YamlReader<Error> {
	// Every key of map node n must be one of allowed.
	void keys(const YAML::Node &n, const std::string &where, std::set<std::string> allowed) const
	{
		if (!n.IsMap())
			fail(n, where + " must be a mapping");
		for (const auto &kv : n) {
			std::string k = kv.first.as<std::string>();
			if (!allowed.count(k)) {
				std::string list;
				for (const auto &a : allowed)
					list += (list.empty() ? "" : ", ") + a;
				fail(kv.first, "unknown key '" + k + "' in " + where + " (allowed: " + list + ")");
			}
		}
	}

	double positive(const YAML::Node &n, const std::string &what) const
	{
		double v = number(n, what);
		if (!(v > 0))
			fail(n, what + " must be > 0");
		return v;
	}

	double non_negative(const YAML::Node &n, const std::string &what) const
	{
		double v = number(n, what);
		if (v < 0)
			fail(n, what + " must be >= 0");
		return v;
	}

	int64_t integer(const YAML::Node &n, const std::string &what, int64_t lo, int64_t hi) const
	{
		double v = number(n, what);
		if (v != std::floor(v) || v < static_cast<double>(lo) || v > static_cast<double>(hi))
			fail(n, what + " must be an integer in [" + std::to_string(lo) + ", " +
					std::to_string(hi) + "]");
		return static_cast<int64_t>(v);
	}

	std::string text(const YAML::Node &n, const std::string &what) const
	{
		if (!n.IsScalar())
			fail(n, what + " must be a string");
		return n.as<std::string>();
	}

	std::vector<double> numbers(const YAML::Node &n, const std::string &what, size_t lo,
				    size_t hi) const
	{
		if (!n.IsSequence())
			fail(n, what + " must be a list of numbers");
		if (n.size() < lo || n.size() > hi)
			fail(n, what + " must have " +
					(lo == hi ? std::to_string(lo)
						  : std::to_string(lo) + " to " + std::to_string(hi)) +
					" entries, not " + std::to_string(n.size()));
		std::vector<double> v;
		for (const auto &e : n)
			v.push_back(number(e, what + " entry"));
		return v;
	}
};

int8_t terrain_class(const Ctx &c, const YAML::Node &n)
{
	std::string s = c.text(n, "class");
	if (s == "ground") return kGround;
	if (s == "water") return kWater;
	if (s == "obstacle") return kObstacle;
	c.fail(n, "unknown terrain class '" + s + "' (ground, water, obstacle)");
}

State state(const Ctx &c, const YAML::Node &n, const std::string &where)
{
	c.keys(n, where, {"mode", "state"});
	State s;
	char names[256];
	YAML::Node m = c.need(n, "mode", where);
	s.mode = mode_of(c.text(m, where + " mode"));
	if (!s.mode)
		c.fail(m, "unknown mode '" + m.as<std::string>() + "' (" + hylo_mode_names(names, sizeof names) + ")");
	size_t dim = static_cast<size_t>(mode_dim(s.mode));
	std::vector<double> x = c.numbers(c.need(n, "state", where), where + " state", dim, dim);
	for (size_t k = 0; k < dim; k++)
		s.x[k] = x[k];
	return s;
}

void paint(const Ctx &c, Scene &sc, const YAML::Node &shape)
{
	std::string type = c.text(c.need(shape, "type", "shape"), "shape type");
	int8_t cls = terrain_class(c, c.need(shape, "class", "shape"));
	double h = shape["height_m"] ? c.number(shape["height_m"], "height_m") : 0.0;
	double x0 = 0, x1 = 0, y0 = 0, y1 = 0, cx = 0, cy = 0, r = 0;
	if (type == "rect") {
		c.keys(shape, "rect shape", {"type", "class", "height_m", "x_m", "y_m"});
		std::vector<double> xs = c.numbers(c.need(shape, "x_m", "rect"), "x_m", 2, 2);
		std::vector<double> ys = c.numbers(c.need(shape, "y_m", "rect"), "y_m", 2, 2);
		if (!(xs[0] < xs[1]) || !(ys[0] < ys[1]))
			c.fail(shape, "rect x_m and y_m must be [low, high] with low < high");
		x0 = xs[0], x1 = xs[1], y0 = ys[0], y1 = ys[1];
	} else if (type == "disc") {
		c.keys(shape, "disc shape", {"type", "class", "height_m", "center_m", "radius_m"});
		std::vector<double> ctr = c.numbers(c.need(shape, "center_m", "disc"), "center_m", 2, 2);
		cx = ctr[0], cy = ctr[1];
		r = c.positive(c.need(shape, "radius_m", "disc"), "radius_m");
	} else {
		c.fail(shape, "unknown shape type '" + type + "' (rect, disc)");
	}
	// A cell belongs to a shape when its centre does.
	for (int32_t iy = 0; iy < sc.ny; iy++)
		for (int32_t ix = 0; ix < sc.nx; ix++) {
			double x = sc.origin_x_m + (ix + 0.5) * sc.resolution_m;
			double y = sc.origin_y_m + (iy + 0.5) * sc.resolution_m;
			bool in = type == "rect" ? (x >= x0 && x < x1 && y >= y0 && y < y1)
						 : ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r);
			if (in) {
				sc.terrain[static_cast<size_t>(iy) * sc.nx + ix] = cls;
				sc.height_m[static_cast<size_t>(iy) * sc.nx + ix] = static_cast<float>(h);
			}
		}
}

Goal goal(const Ctx &c, const YAML::Node &n)
{
	c.keys(n, "goal", {"start", "goal", "algorithm", "seed", "spacing_m", "air_spacing_m",
			   "guard_spacing_m", "connect_radius_m", "air_connect_radius_m",
			   "speeds_mps", "headings_rad", "air_speeds_mps", "time_budget_ms", "suboptimality",
			   "max_expansions", "alternatives", "alternatives_within"});
	Goal g;
	g.start = state(c, c.need(n, "start", "goal"), "start");
	g.goal = state(c, c.need(n, "goal", "goal"), "goal");
	if (n["algorithm"]) {
		std::string a = c.text(n["algorithm"], "algorithm");
		if (a == "astar") g.algorithm = 0;
		else if (a == "dijkstra") g.algorithm = 1;
		else c.fail(n["algorithm"], "unknown algorithm '" + a + "' (astar, dijkstra)");
	}
	if (n["seed"])
		g.seed = c.integer(n["seed"], "seed", 0, INT64_C(1) << 53);
	g.spacing_m = c.positive(c.need(n, "spacing_m", "goal"), "spacing_m");
	g.guard_spacing_m = c.positive(c.need(n, "guard_spacing_m", "goal"), "guard_spacing_m");
	g.connect_radius_m = c.positive(c.need(n, "connect_radius_m", "goal"), "connect_radius_m");
	if (n["air_spacing_m"])
		g.air_spacing_m = c.positive(n["air_spacing_m"], "air_spacing_m");
	if (n["air_connect_radius_m"])
		g.air_connect_radius_m = c.positive(n["air_connect_radius_m"], "air_connect_radius_m");
	if (n["speeds_mps"])
		g.speeds_mps = c.numbers(n["speeds_mps"], "speeds_mps", 0, 1024);
	if (n["headings_rad"])
		g.headings_rad = c.numbers(n["headings_rad"], "headings_rad", 0, 1024);
	if (n["air_speeds_mps"])
		g.air_speeds_mps = c.numbers(n["air_speeds_mps"], "air_speeds_mps", 0, 1024);
	if (n["time_budget_ms"])
		g.time_budget_ms = c.non_negative(n["time_budget_ms"], "time_budget_ms");
	if (n["suboptimality"]) {
		g.suboptimality = c.non_negative(n["suboptimality"], "suboptimality");
		if (g.suboptimality != 0 && g.suboptimality < 1)
			c.fail(n["suboptimality"], "suboptimality must be 0 (the optimum) or >= 1");
	}
	if (n["max_expansions"])
		g.max_expansions = static_cast<int32_t>(
			c.integer(n["max_expansions"], "max_expansions", 0, INT32_MAX));
	if (n["alternatives"])
		g.alternatives = static_cast<int>(c.integer(n["alternatives"], "alternatives", 0, 8));
	if (n["alternatives_within"]) {
		g.alternatives_within = c.non_negative(n["alternatives_within"], "alternatives_within");
		if (g.alternatives_within != 0 && g.alternatives_within < 1)
			c.fail(n["alternatives_within"], "alternatives_within must be 0 (the default) or >= 1");
	}
	return g;
}

}  // namespace

int mode_of(const std::string &name)
{
	return hylo_mode_parse(name.c_str());
}

const char *mode_name(int mode)
{
	return mode == HYLO_MODE_NONE ? "none" : hylo_mode_str(static_cast<hylo_mode>(mode));
}

int mode_dim(int mode)
{
	return static_cast<int>(hylo_mode_dim(static_cast<hylo_mode>(mode)));
}

State parse_state(const std::string &text, const std::string &what)
{
	size_t colon = text.find(':');
	if (colon == std::string::npos)
		throw Error(what + ": expected MODE:x1,x2,... (e.g. ground:2,16,0,0), got '" + text + "'");
	State s;
	s.mode = mode_of(text.substr(0, colon));
	if (!s.mode)
		throw Error(what + ": unknown mode '" + text.substr(0, colon) + "'");
	std::stringstream ss(text.substr(colon + 1));
	std::string item;
	int k = 0;
	while (std::getline(ss, item, ',')) {
		size_t used = 0;
		double v = 0;
		try {
			v = std::stod(item, &used);
		} catch (const std::exception &) {
			used = 0;
		}
		if (used != item.size() || item.empty() || !std::isfinite(v))
			throw Error(what + ": '" + item + "' is not a finite number");
		if (k >= mode_dim(s.mode))
			throw Error(what + ": mode " + mode_name(s.mode) + " takes " +
				    std::to_string(mode_dim(s.mode)) + " coordinates");
		s.x[static_cast<size_t>(k++)] = v;
	}
	if (k != mode_dim(s.mode))
		throw Error(what + ": mode " + std::string(mode_name(s.mode)) + " takes " +
			    std::to_string(mode_dim(s.mode)) + " coordinates, got " + std::to_string(k));
	return s;
}

Scene load(const std::string &path)
{
	Ctx c{{path}};
	YAML::Node root = trainer::load_yaml_mapping<Error>(path, "a scene");
	c.keys(root, "the scene", {"name", "description", "robot", "map_id", "grid", "ceiling_m",
				   "max_step_m", "terrain", "goal", "render"});
	Scene sc;
	sc.path = path;
	if (root["name"])
		sc.name = c.text(root["name"], "name");
	if (root["description"])
		sc.description = c.text(root["description"], "description");
	sc.robot = c.text(c.need(root, "robot", "the scene"), "robot");
	if (sc.robot.empty() || sc.robot.size() > 31)
		c.fail(root["robot"], "robot must have 1 to 31 characters");
	if (root["map_id"])
		sc.map_id = c.integer(root["map_id"], "map_id", 1, INT64_C(1) << 53);
	YAML::Node grid = c.need(root, "grid", "the scene");
	c.keys(grid, "grid", {"nx", "ny", "resolution_m", "origin_m"});
	sc.nx = static_cast<int32_t>(c.integer(c.need(grid, "nx", "grid"), "nx", 1, 4096));
	sc.ny = static_cast<int32_t>(c.integer(c.need(grid, "ny", "grid"), "ny", 1, 4096));
	sc.resolution_m = c.positive(c.need(grid, "resolution_m", "grid"), "resolution_m");
	if (grid["origin_m"]) {
		std::vector<double> o = c.numbers(grid["origin_m"], "origin_m", 2, 2);
		sc.origin_x_m = o[0];
		sc.origin_y_m = o[1];
	}
	if (root["ceiling_m"])
		sc.ceiling_m = c.non_negative(root["ceiling_m"], "ceiling_m");
	if (root["max_step_m"])
		sc.max_step_m = c.non_negative(root["max_step_m"], "max_step_m");
	size_t n = static_cast<size_t>(sc.nx) * static_cast<size_t>(sc.ny);
	sc.terrain.assign(n, kGround);
	sc.height_m.assign(n, 0.0f);
	if (YAML::Node t = root["terrain"]) {
		c.keys(t, "terrain", {"default", "default_height_m", "shapes"});
		if (t["default"])
			sc.terrain.assign(n, terrain_class(c, t["default"]));
		if (t["default_height_m"])
			sc.height_m.assign(n, static_cast<float>(c.number(t["default_height_m"], "default_height_m")));
		if (YAML::Node shapes = t["shapes"]) {
			if (!shapes.IsSequence())
				c.fail(shapes, "terrain shapes must be a list");
			for (const auto &s : shapes) {
				if (!s.IsMap())
					c.fail(s, "a shape must be a mapping");
				paint(c, sc, s);
			}
		}
	}
	if (root["goal"]) {
		sc.goal = goal(c, root["goal"]);
		sc.has_goal = true;
	}
	if (YAML::Node r = root["render"]) {
		c.keys(r, "render", {"camera_azimuth_deg", "camera_elevation_deg", "camera_distance_m"});
		if (r["camera_azimuth_deg"])
			sc.camera_azimuth_deg = c.number(r["camera_azimuth_deg"], "camera_azimuth_deg");
		if (r["camera_elevation_deg"]) {
			sc.camera_elevation_deg = c.number(r["camera_elevation_deg"], "camera_elevation_deg");
			if (std::fabs(sc.camera_elevation_deg) > 89)
				c.fail(r["camera_elevation_deg"], "camera_elevation_deg must be in [-89, 89]");
		}
		if (r["camera_distance_m"])
			sc.camera_distance_m = c.non_negative(r["camera_distance_m"], "camera_distance_m");
	}
	return sc;
}

}  // namespace hylo::scene
