// Reading a YAML file, with the errors the robot files (trainer/params.cpp)
// and scenes (tools/scene/scene.cpp) give. Header-only: each caller throws
// its own exception type.
#ifndef HYLO_TRAINER_YAML_FILE_HPP
#define HYLO_TRAINER_YAML_FILE_HPP

#include <cmath>
#include <string>

#include <yaml-cpp/yaml.h>

namespace hylo::trainer {

// The root of the YAML file at path. Throws Error (constructed from a
// string) "PATH: cannot read the file", "PATH:LINE: YAML syntax: ..." or,
// when the root is not a mapping, "PATH:1: WHAT must be a YAML mapping".
template <class Error>
YAML::Node load_yaml_mapping(const std::string &path, const std::string &what)
{
	YAML::Node root;
	try {
		root = YAML::LoadFile(path);
	} catch (const YAML::BadFile &) {
		throw Error(path + ": cannot read the file");
	} catch (const YAML::ParserException &e) {
		throw Error(path + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax: " + e.msg);
	}
	if (!root || !root.IsMap())
		throw Error(path + ":1: " + what + " must be a YAML mapping");
	return root;
}

// The nodes of the YAML file path, read with errors Error "PATH:LINE: what"
// (LINE: the node's).
template <class Error>
struct YamlReader {
	std::string path;

	[[noreturn]] void fail(const YAML::Node &n, const std::string &what) const
	{
		int line = n.Mark().line >= 0 ? n.Mark().line + 1 : 0;
		throw Error(path + ":" + std::to_string(line) + ": " + what);
	}

	YAML::Node need(const YAML::Node &n, const std::string &key, const std::string &where) const
	{
		YAML::Node v = n[key];
		if (!v)
			fail(n, "missing key '" + key + "' in " + where);
		return v;
	}

	double number(const YAML::Node &n, const std::string &what) const
	{
		double v = 0;
		try {
			v = n.as<double>();
		} catch (const YAML::Exception &) {
			fail(n, what + " must be a number");
		}
		if (!std::isfinite(v))
			fail(n, what + " must be finite");
		return v;
	}
};

}  // namespace hylo::trainer

#endif
