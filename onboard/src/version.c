#include "hylo/version.h"

const char *hylo_version(void)
{
	return HYLO_VERSION;
}
