// The command line of the trainer's programs and the C++ tools: an option's
// value, and main's report of what run() threw.
#ifndef HYLO_TRAINER_CLI_HPP
#define HYLO_TRAINER_CLI_HPP

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

namespace hylo::trainer {

// The value after option argv[i]; i moves onto it. Throws
// std::invalid_argument "OPTION needs a value" when there is none.
inline std::string option_value(int argc, char **argv, int &i)
{
	if (i + 1 >= argc)
		throw std::invalid_argument(std::string(argv[i]) + " needs a value");
	return argv[++i];
}

// main's body: run(argc, argv), an exception it throws printed as "PROG:
// what" (and usage after it, when given, for a bad command line), with exit
// status usage_status for std::invalid_argument (a bad command line) and 1
// for any other.
inline int run_main(const char *prog, int (*run)(int, char **), int argc, char **argv, int usage_status = 2,
		    const char *usage = "")
{
	try {
		return run(argc, argv);
	} catch (const std::invalid_argument &e) {
		std::fprintf(stderr, "%s: %s\n%s", prog, e.what(), usage);
		return usage_status;
	} catch (const std::exception &e) {
		std::fprintf(stderr, "%s: %s\n", prog, e.what());
		return 1;
	}
}

}  // namespace hylo::trainer

#endif
