#include "trainer/modes.hpp"

#include "trainer/models.hpp"

namespace hylo::trainer {

bool known_mode(const std::string &m)
{
	return m == "ground" || m == "marine" || m == "flight" || m == "di_neg" || m == "di_pos";
}

namespace {
const char *const kModeNames[] = {"", "ground", "marine", "flight", "di_neg", "di_pos"};
}  // namespace

std::string mode_name(int m)
{
	return m >= 1 && m <= 5 ? kModeNames[m] : "";
}

int mode_number(const std::string &mode)
{
	for (int m = 1; m <= 5; m++)
		if (mode == kModeNames[m])
			return m;
	return 0;
}

int sampled_dim(const std::string &m)
{
	if (m == "ground" || m == "marine")
		return 4;
	if (m == "flight")
		return 6;
	if (m == "di_neg" || m == "di_pos")
		return 2;
	return 0;
}

int state_dim(const std::string &m)
{
	if (m == "ground")
		return GroundModel::NX;
	if (m == "marine")
		return MarineModel::NX;
	if (m == "flight")
		return FlightModel::NX;
	return known_mode(m) ? DiModel::NX : 0;
}

int input_dim(const std::string &m)
{
	if (m == "ground")
		return GroundModel::NU;
	if (m == "marine")
		return MarineModel::NU;
	if (m == "flight")
		return FlightModel::NU;
	return known_mode(m) ? DiModel::NU : 0;
}

}  // namespace hylo::trainer
