// A C++17 program against an installed hylo through find_package(hylo)
// and hylo::onboard, hylo::lcm (tests/install/test_install.sh). It plans the
// double integrator's scene with the committed models (../consumer.h: the
// C headers need no extern "C" of the caller's), and round-trips a plan_t
// through the installed C++ LCM binding (header-only) and the C adaptors.
#include <cstdint>
#include <cstdio>
#include <vector>

#include <hylo/plan_t.hpp>
#include <hylo_msg.h>

#include "../consumer.h"

int main()
{
	int rc = consumer_plan();
	hylo::plan_t m;
	m.utime = 1;
	m.request_id = 7;
	m.map_id = 1;
	m.status = hylo_msg_plan_status(HYLO_OK, HYLO_FOUND);
	m.reason = "ok";
	m.robot = "di";
	m.total_cost_j = 2.5;
	m.suboptimality = 1;
	m.lower_bound_j = 0;
	m.n_waypoints = 0;
	m.n_modes = 0;
	m.n_nodes = 0;
	m.n_edges = m.n_edges_evaluated = m.n_edges_cached = m.n_expansions = m.n_clamped = 0;
	m.plan_ms = 0;
	std::vector<uint8_t> buf(static_cast<size_t>(m.getEncodedSize()));
	hylo::plan_t back;
	if (m.encode(buf.data(), 0, static_cast<int>(buf.size())) != static_cast<int>(buf.size()) ||
	    back.decode(buf.data(), 0, static_cast<int>(buf.size())) != static_cast<int>(buf.size()) ||
	    back.total_cost_j != 2.5 || back.robot != "di" || back.status != hylo::plan_t::STATUS_OK) {
		std::fprintf(stderr, "consumer: plan_t did not round-trip\n");
		rc = 1;
	} else {
		std::printf("plan_t round-trips through the C++ binding (%zu bytes)\n", buf.size());
	}
	return rc;
}
