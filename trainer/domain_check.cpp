#include "trainer/domain_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "hylo/modes.h"

namespace hylo::trainer {
namespace {

// Distance from (x, y) to the nearest cell of terrain class cls within
// reach (infinity if none): 0 on such a cell.
double distance_to_class(const TerrainGrid &m, double x, double y, int8_t cls, double reach)
{
	GridCell c = cell_at(m, x, y);
	if (!c.inside)
		return std::numeric_limits<double>::infinity();
	if (m.terrain[static_cast<size_t>(c.index)] == cls)
		return 0;
	const int cx = c.index % m.nx, cy = c.index / m.nx;
	const int span = static_cast<int>(std::ceil(reach / m.resolution_m)) + 1;
	double best = std::numeric_limits<double>::infinity();
	for (int iy = std::max(0, cy - span); iy <= std::min(m.ny - 1, cy + span); iy++)
		for (int ix = std::max(0, cx - span); ix <= std::min(m.nx - 1, cx + span); ix++) {
			if (m.terrain[static_cast<size_t>(iy * m.nx + ix)] != cls)
				continue;
			double x0 = m.origin_x_m + ix * m.resolution_m, y0 = m.origin_y_m + iy * m.resolution_m;
			double dx = std::max({x0 - x, 0.0, x - (x0 + m.resolution_m)});
			double dy = std::max({y0 - y, 0.0, y - (y0 + m.resolution_m)});
			best = std::min(best, std::hypot(dx, dy));
		}
	return best;
}

}  // namespace

double domain_tolerance_m(const TerrainGrid &map)
{
	return map.resolution_m;
}

DomainCheck domain_check(const MultiPhaseSolution &s, const TerrainGrid &map)
{
	DomainCheck d;
	if (map.nx <= 0 || map.ny <= 0)
		return d;
	const double reach = 4 * domain_tolerance_m(map);
	double t0 = 0;
	for (size_t k = 0; k < s.phases.size(); k++) {
		const Trajectory &tr = s.phases[k].traj;
		const hylo_mode mode = s.modes[k];
		const hylo_domain_kind domain = hylo_mode_domain(mode);
		const bool surface = domain == HYLO_DOMAIN_LAND || domain == HYLO_DOMAIN_WATER;
		if (surface || domain == HYLO_DOMAIN_AIR)   // a phase plane has no terrain class
			for (size_t i = 0; i < tr.t.size(); i++) {
				const double *x = &tr.x[i * static_cast<size_t>(tr.nx)];
				double out;
				if (surface) {
					out = distance_to_class(map, x[0], x[1], domain == HYLO_DOMAIN_LAND ? kGround : kWater, reach);
				} else {
					GridCell c = cell_at(map, x[0], x[1]);
					out = c.inside ? std::max(0.0, map.height_m[static_cast<size_t>(c.index)] - x[2])
						       : std::numeric_limits<double>::infinity();
				}
				if (out > d.worst_m) {
					d = {out, static_cast<int>(k), mode, t0 + tr.t[i], x[0], x[1], reach};
				}
			}
		t0 += s.phases[k].T;
	}
	return d;
}

std::string DomainCheck::text() const
{
	if (phase < 0)
		return "inside its domain";
	char buf[200];
	const hylo_domain_kind domain = hylo_mode_domain(mode);
	const char *what = domain == HYLO_DOMAIN_LAND ? "m from ground" : domain == HYLO_DOMAIN_WATER ? "m from water" : "m below the terrain";
	if (std::isfinite(worst_m))
		std::snprintf(buf, sizeof buf, "phase %d (%s) at t = %.3g s, (%.3g, %.3g) m: %.3g %s", phase, hylo_mode_str(mode),
			      t_s, x_m, y_m, worst_m, what);
	else   // off the map, or farther than domain_check looks
		std::snprintf(buf, sizeof buf, "phase %d (%s) at t = %.3g s, (%.3g, %.3g) m: off the map or over %.3g %s",
			      phase, hylo_mode_str(mode), t_s, x_m, y_m, reach_m, what);
	return buf;
}

}  // namespace hylo::trainer
