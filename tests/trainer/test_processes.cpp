// The trainer's worker pool (trainer/processes.hpp): fork_chunks hands
// results over a chunk at a time in index order, keeps the workers busy
// with the next chunk while a slow item holds the current one back, gives
// an empty result for an item whose process died, and kills its children
// when the chunk handler throws; fork_each returns every result. No
// solves. Prints TAP.
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "tests/tap.hpp"
#include "trainer/processes.hpp"

namespace {

using namespace hylo::trainer;
namespace fs = std::filesystem;

// Waits up to 60 s for path to exist.
bool wait_for(const fs::path &path)
{
	for (int k = 0; k < 6000; k++) {
		if (fs::exists(path))
			return true;
		std::this_thread::sleep_for(std::chrono::milliseconds(10));
	}
	return false;
}

// Writes this process's pid to path, whole or not at all: the file appears
// by a rename, so a reader that sees it also sees the pid (the writer may be
// killed at any moment after).
void touch(const fs::path &path)
{
	const fs::path tmp = path.string() + ".tmp" + std::to_string(getpid());
	std::ofstream(tmp) << getpid() << "\n";
	fs::rename(tmp, path);
}

}  // namespace

int main()
{
	const fs::path dir = fs::temp_directory_path() / ("hylo_test_processes_" + std::to_string(getpid()));
	fs::create_directories(dir);

	// Order and chunks: 10 items in chunks of 4 with 3 workers.
	{
		std::vector<size_t> firsts;
		std::vector<std::string> all;
		fork_chunks(10, 3, 4, [](size_t i) { return "item " + std::to_string(i); },
			    [&](size_t first, std::vector<std::string> &r) {
				    firsts.push_back(first);
				    all.insert(all.end(), r.begin(), r.end());
			    });
		bool ordered = all.size() == 10;
		for (size_t i = 0; ordered && i < all.size(); i++)
			ordered = all[i] == "item " + std::to_string(i);
		check(firsts == std::vector<size_t>{0, 4, 8} && ordered,
		      "chunks of 4 of 10 items come at 0, 4 and 8, every result in index order");
	}

	// A slow item does not stop the other worker at its chunk's end: item 0
	// waits for item 7 (the next chunk's last) to have run. Without the
	// look-ahead it would wait for ever (here: 60 s, then say so).
	{
		const fs::path flag = dir / "item7";
		std::vector<std::string> all;
		fork_chunks(8, 2, 4,
			    [&](size_t i) {
				    if (i == 7)
					    touch(flag);
				    if (i == 0)
					    return std::string(wait_for(flag) ? "saw 7" : "timed out");
				    return std::to_string(i);
			    },
			    [&](size_t, std::vector<std::string> &r) { all.insert(all.end(), r.begin(), r.end()); });
		check(all.size() == 8 && all[0] == "saw 7",
		      "while item 0 runs, the other worker solves the next chunk's items",
		      all.empty() ? "no results" : "item 0: " + all[0]);
	}

	// An item whose process dies, or whose result is too long, is empty.
	{
		std::vector<std::string> r = fork_each(
			4, 2,
			[](size_t i) -> std::string {
				if (i == 1)
					std::abort();
				if (i == 2)
					return std::string(100, 'x');
				return "fine";
			},
			16);
		check(r.size() == 4 && r[0] == "fine" && r[1].empty() && r[2].empty() && r[3] == "fine",
		      "a process that died and a result over max_bytes come back empty");
	}

	// The handler throws: the exception comes out, and the worker still
	// running (item 2 of the next chunk, which would sleep 60 s) is killed.
	{
		const fs::path pid_file = dir / "sleeper";
		std::string what;
		try {
			fork_chunks(4, 2, 2,
				    [&](size_t i) {
					    if (i == 2) {
						    touch(pid_file);
						    std::this_thread::sleep_for(std::chrono::seconds(60));
					    }
					    return std::to_string(i);
				    },
				    [&](size_t first, std::vector<std::string> &) {
					    if (first == 0) {
						    wait_for(pid_file);   // item 2 is running
						    throw std::runtime_error("disk full");
					    }
				    });
		} catch (const std::runtime_error &e) {
			what = e.what();
		}
		pid_t sleeper = 0;
		std::ifstream(pid_file) >> sleeper;
		bool gone = sleeper > 0 && kill(sleeper, 0) != 0 && errno == ESRCH;
		check(what == "disk full" && gone,
		      "a throwing handler's exception comes out and the running worker is killed",
		      "exception '" + what + "', sleeper " + std::to_string(sleeper) + (gone ? " gone" : " alive"));
	}

	check(fork_each(0, 2, [](size_t) { return std::string("x"); }).empty(), "no items, no results");
	fs::remove_all(dir);
	return tap_finish();
}
