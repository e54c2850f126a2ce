// TAP output for the C++ tests: check() prints "ok N - name" or "not ok N -
// name" with the reason as a "# " line; tap_finish() prints the plan and
// gives main's exit code.
#ifndef HYLO_TESTS_TAP_HPP
#define HYLO_TESTS_TAP_HPP

#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

namespace tap {
inline int n_checks = 0, n_failed = 0;
}

inline void check(bool ok, const std::string &name, const std::string &why = "")
{
	tap::n_checks++;
	std::printf("%s %d - %s\n", ok ? "ok" : "not ok", tap::n_checks, name.c_str());
	if (!ok) {
		tap::n_failed++;
		if (!why.empty())
			std::printf("# %s\n", why.c_str());
	}
	std::fflush(stdout);
}

// f throws std::invalid_argument with needle in its message.
inline void check_throws(const std::function<void()> &f, const std::string &needle, const std::string &name)
{
	try {
		f();
		check(false, name, "no exception");
	} catch (const std::invalid_argument &e) {
		check(std::string(e.what()).find(needle) != std::string::npos, name, e.what());
	}
}

// v to the given significant digits ("%.*g"), for names and reasons.
inline std::string tap_num(double v, int digits)
{
	char b[64];
	std::snprintf(b, sizeof b, "%.*g", digits, v);
	return b;
}

inline int tap_finish()
{
	std::printf("1..%d\n", tap::n_checks);
	return tap::n_failed ? 1 : 0;
}

#endif
