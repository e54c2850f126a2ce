// Reading a YAML file whose top level is a mapping, with the errors the
// robot files (trainer/params.cpp) and scenes (tools/scene/scene.cpp) give.
// Header-only: each caller throws its own exception type.
#ifndef HYLO_TRAINER_YAML_FILE_HPP
#define HYLO_TRAINER_YAML_FILE_HPP

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

}  // namespace hylo::trainer

#endif
