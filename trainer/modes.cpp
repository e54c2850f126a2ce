#include "trainer/modes.hpp"

#include <stdexcept>
#include <string>

namespace hylo::trainer {

hylo_mode parse_mode(const std::string &name)
{
	hylo_mode m = hylo_mode_parse(name.c_str());
	if (m == HYLO_MODE_NONE)
		throw std::invalid_argument("unknown mode '" + name + "' (" + mode_list() + ")");
	return m;
}

const hylo_mode_desc &mode_desc(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);
	if (!d)
		throw std::invalid_argument("unknown mode " + std::to_string(static_cast<int>(mode)) + " (" +
					    mode_list() + ")");
	return *d;
}

std::string mode_list()
{
	char buf[256];
	return hylo_mode_names(buf, sizeof buf);
}

bool known_mode(const std::string &m)
{
	return hylo_mode_parse(m.c_str()) != HYLO_MODE_NONE;
}

std::string mode_name(int m)
{
	const hylo_mode_desc *d = hylo_mode_describe(static_cast<hylo_mode>(m));
	return d ? d->name : "";
}

}  // namespace hylo::trainer
