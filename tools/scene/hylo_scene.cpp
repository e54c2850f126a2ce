// hylo-scene: validates a scene file and publishes its map (and, with
// --goal, its default goal) on LCM. See --help. Exit codes: 0 published (or
// valid, with --check), 1 invalid scene or LCM failure, 2 usage error.
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>

#include <unistd.h>

#include <lcm/lcm-cpp.hpp>

#include "hylo_msg.h"
#include "tools/scene/planner_view.hpp"
#include "tools/scene/scene.hpp"
#include "trainer/cli.hpp"

namespace {

using hylo::scene::Scene;

void usage(FILE *f)
{
	std::fprintf(f,
		"usage: hylo-scene SCENE.yaml [options]\n"
		"Validates a scene file (format: scenes/README.md) and publishes its map on\n"
		"<prefix>HYLO_MAP, and with --goal its default goal on <prefix>HYLO_GOAL.\n"
		"\n"
		"  --goal                 also publish the scene's goal\n"
		"  --start MODE:x,...     override the goal's start (e.g. ground:2,16,0,0)\n"
		"  --goal-state MODE:x,.. override the goal's goal state\n"
		"  --request-id N         request id of the goal (default: 1)\n"
		"  --alternatives K       ask for the best paths of K distinct mode sequences, 0-8\n"
		"                         (on <prefix>HYLO_PLAN_ALTERNATIVE; 1: the plan only;\n"
		"                         0: goal_t.DEFAULT_ALTERNATIVES = 3; default: the scene's)\n"
		"  --seed N               override the sampling seed\n"
		"  --lcm-url URL          LCM provider (default: $LCM_DEFAULT_URL, else LCM's default)\n"
		"  --channel-prefix P     prefix of the channel names (default: none)\n"
		"  --check                validate and print a summary; publish nothing\n"
		"  --print-camera         print the render camera as AZ,EL,DIST (hylo-render --camera)\n"
		"  --help                 this text\n");
}

void wire_grid(const std::vector<double> &v, int32_t *n, double **values)
{
	*n = static_cast<int32_t>(v.size());
	*values = const_cast<double *>(v.data());
}

int64_t utime_now()
{
	struct timespec t;
	clock_gettime(CLOCK_REALTIME, &t);
	return static_cast<int64_t>(t.tv_sec) * 1000000 + t.tv_nsec / 1000;
}

void summary(const Scene &sc)
{
	size_t counts[3] = {0, 0, 0};
	for (int8_t t : sc.terrain)
		counts[t >= 0 && t < 3 ? t : 0]++;
	std::printf("%s: robot %s, map %lld, %d x %d cells of %g m (%zu ground, %zu water, %zu "
		    "obstacle), ceiling %g m\n",
		    sc.path.c_str(), sc.robot.c_str(), static_cast<long long>(sc.map_id), sc.nx,
		    sc.ny, sc.resolution_m, counts[1], counts[2], counts[0], sc.ceiling_m);
	if (sc.has_goal) {
		const auto &g = sc.goal;
		std::printf("goal: %s (%g, %g) -> %s (%g, %g), seed %lld, spacing %g m\n",
			    hylo::scene::mode_name(g.start.mode), g.start.x[0], g.start.x[1],
			    hylo::scene::mode_name(g.goal.mode), g.goal.x[0], g.goal.x[1],
			    static_cast<long long>(g.seed), g.spacing_m);
	}
}

int run(int argc, char **argv)
{
	std::string path, url, prefix, start, goal_state;
	bool with_goal = false, check = false, print_camera = false;
	int64_t request_id = 1, seed = -1;
	int alternatives = -1;
	for (int i = 1; i < argc; i++) {
		std::string a = argv[i];
		auto value = [&] { return hylo::trainer::option_value(argc, argv, i); };
		if (a == "--help" || a == "-h") {
			usage(stdout);
			return 0;
		} else if (a == "--goal") {
			with_goal = true;
		} else if (a == "--check") {
			check = true;
		} else if (a == "--print-camera") {
			print_camera = true;
		} else if (a == "--start") {
			start = value();
		} else if (a == "--goal-state") {
			goal_state = value();
		} else if (a == "--lcm-url") {
			url = value();
		} else if (a == "--channel-prefix") {
			prefix = value();
		} else if (a == "--alternatives") {
			std::string v = value();
			if (v.size() != 1 || v[0] < '0' || v[0] > '8')
				throw std::invalid_argument("--alternatives needs a number from 0 to 8, not '" + v + "'");
			alternatives = v[0] - '0';
		} else if (a == "--request-id" || a == "--seed") {
			std::string v = value();
			size_t used = 0;
			long long n = 0;
			try {
				n = std::stoll(v, &used);
			} catch (const std::exception &) {
				used = 0;
			}
			if (used != v.size() || n < 0)
				throw std::invalid_argument(a + " needs a non-negative integer, not '" + v + "'");
			(a == "--seed" ? seed : request_id) = n;
		} else if (!a.empty() && a[0] == '-') {
			throw std::invalid_argument("unknown option '" + a + "' (see --help)");
		} else if (path.empty()) {
			path = a;
		} else {
			throw std::invalid_argument("more than one scene file given");
		}
	}
	if (path.empty())
		throw std::invalid_argument("no scene file given (see --help)");

	Scene sc = hylo::scene::load(path);
	if ((with_goal || !start.empty() || !goal_state.empty()) && !sc.has_goal)
		throw hylo::scene::Error(path + ": the scene has no goal section");
	if (!start.empty())
		sc.goal.start = hylo::scene::parse_state(start, "--start");
	if (!goal_state.empty())
		sc.goal.goal = hylo::scene::parse_state(goal_state, "--goal-state");
	if (seed >= 0)
		sc.goal.seed = seed;
	if (alternatives >= 0)
		sc.goal.alternatives = alternatives;
	if (check) {
		summary(sc);
		return 0;
	}
	if (print_camera) {
		std::printf("%.17g,%.17g,%.17g\n", sc.camera_azimuth_deg, sc.camera_elevation_deg,
			    sc.camera_distance_m);
		return 0;
	}
	lcm::LCM lcm(url);
	if (!lcm.good()) {
		std::fprintf(stderr, "hylo-scene: cannot open LCM provider '%s'\n",
			     url.empty() ? "(default)" : url.c_str());
		return 1;
	}
	const hylo_map_view view = map_view(sc);
	hylo_map_t map;
	hylo_msg_map(&view, &map);
	map.utime = utime_now();
	if (hylo_map_t_publish(lcm.getUnderlyingLCM(), (prefix + "HYLO_MAP").c_str(), &map) != 0) {
		std::fprintf(stderr, "hylo-scene: publishing the map failed\n");
		return 1;
	}
	if (with_goal) {
		hylo_goal request = goal_of(sc);
		request.request_id = request_id;
		request.map_id = sc.map_id;
		hylo_goal_t goal;
		hylo_msg_goal(&request, &goal);
		goal.utime = utime_now();
		goal.requester_id = getpid();   // as hylo_client.py: each publisher its own queue slot
		// As the scene says: alternatives 0 is the default, and a grid may be
		// longer than a hylo_goal holds (the node refuses it then).
		goal.alternatives = static_cast<int8_t>(sc.goal.alternatives);
		wire_grid(sc.goal.speeds_mps, &goal.n_speeds, &goal.speeds_mps);
		wire_grid(sc.goal.headings_rad, &goal.n_headings, &goal.headings_rad);
		wire_grid(sc.goal.air_speeds_mps, &goal.n_air_speeds, &goal.air_speeds_mps);
		if (hylo_goal_t_publish(lcm.getUnderlyingLCM(), (prefix + "HYLO_GOAL").c_str(), &goal) != 0) {
			std::fprintf(stderr, "hylo-scene: publishing the goal failed\n");
			return 1;
		}
	}
	return 0;
}

}  // namespace

int main(int argc, char **argv)
{
	return hylo::trainer::run_main("hylo-scene", run, argc, argv);
}
