#include "trainer/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "trainer/modes.hpp"

extern "C" {
#include "hylo/clearance.h"
}

namespace hylo::trainer {
namespace {

// A state's position and its velocity in the world frame (the kinematics
// of docs/models.md sections 3-5).
struct Motion {
	double p[3], v[3];
};

Motion motion(const hylo_mode_desc &mode, const double *x)
{
	Motion m{};
	if (mode.air) {   // flight: (p, body-frame velocity, ..., roll, pitch, yaw, ...)
		const double cr = std::cos(x[6]), sr = std::sin(x[6]), cp = std::cos(x[7]), sp = std::sin(x[7]),
			     cy = std::cos(x[8]), sy = std::sin(x[8]);
		const double R[3][3] = {{cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr},
					{sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr},
					{-sp, cp * sr, cp * cr}};
		for (int i = 0; i < 3; i++) {
			m.p[i] = x[i];
			m.v[i] = R[i][0] * x[3] + R[i][1] * x[4] + R[i][2] * x[5];
		}
	} else {   // ground, marine: (px, py, vx, vy, theta, ...)
		const double c = std::cos(x[4]), s = std::sin(x[4]);
		m.p[0] = x[0];
		m.p[1] = x[1];
		m.v[0] = x[2] * c - x[3] * s;
		m.v[1] = x[2] * s + x[3] * c;
	}
	return m;
}

// The cubic Hermite position between a (at 0) and b (at h) at fraction f.
hylo_point between(const Motion &a, const Motion &b, double h, double f)
{
	const double h00 = (1 + 2 * f) * (1 - f) * (1 - f), h10 = f * (1 - f) * (1 - f), h01 = f * f * (3 - 2 * f),
		     h11 = f * f * (f - 1);
	double q[3];
	for (int i = 0; i < 3; i++)
		q[i] = h00 * a.p[i] + h10 * h * a.v[i] + h01 * b.p[i] + h11 * h * b.v[i];
	return {q[0], q[1], q[2]};
}

// In the domain, or within tolerance of it: optimal trajectories sit on
// their bounds, which Ipopt meets to ~1e-8 (its bound relaxation).
bool in_domain(const hylo_map *m, hylo_mode mode, hylo_point p)
{
	if (hylo_domain_contains(m, mode, p))
		return true;
	const double d[4][3] = {{kCheckToleranceM, 0, 0}, {-kCheckToleranceM, 0, 0}, {0, kCheckToleranceM, 0},
				{0, -kCheckToleranceM, 0}};
	for (const auto &e : d) {
		hylo_point q = {p.x + e[0], p.y + e[1], p.z + (mode == HYLO_MODE_FLIGHT ? kCheckToleranceM : 0)};
		if (hylo_domain_contains(m, mode, q))
			return true;
	}
	return false;
}

}  // namespace

std::unique_ptr<hylo_map> onboard_map(const TerrainGrid &g)
{
	const size_t cells = static_cast<size_t>(std::max(g.nx, 0)) * static_cast<size_t>(std::max(g.ny, 0));
	if (g.terrain.size() != cells || g.height_m.size() != cells)
		throw std::invalid_argument("the map's terrain and heights are not nx * ny cells");
	double ceiling = g.ceiling_m;
	if (!std::isfinite(ceiling))   // no ceiling: far above the highest cell
		ceiling = (g.height_m.empty() ? 0.0 : *std::max_element(g.height_m.begin(), g.height_m.end())) + 1e4;
	auto m = std::make_unique<hylo_map>();
	hylo_map_view v{};
	v.map_id = 1;
	v.robot = "smoother";
	v.nx = g.nx;
	v.ny = g.ny;
	v.resolution = g.resolution_m;
	v.origin_x = g.origin_x_m;
	v.origin_y = g.origin_y_m;
	v.ceiling = ceiling;
	v.max_step = g.max_step_m;
	v.n_cells = g.nx * g.ny;
	v.terrain = g.terrain.data();
	v.height = g.height_m.data();
	hylo_reason why;
	if (hylo_map_ingest(m.get(), &v, &why) != HYLO_OK)
		throw std::invalid_argument(std::string("the onboard code refuses the map: ") + why.text);
	return m;
}

ClearanceCheck check_clearance(const MultiPhaseSolution &s, const TerrainGrid &map, double body_radius_m,
			       double margin_m, int between_knots)
{
	ClearanceCheck c;
	c.body_radius_m = body_radius_m;
	c.margin_m = margin_m;
	c.min_clearance_m = margin_m + kClearanceReachM;
	if (map.nx <= 0 || map.ny <= 0)
		return c;
	const auto m = onboard_map(map);
	const double reach = body_radius_m + margin_m + kClearanceReachM;
	double t0 = 0;
	for (size_t k = 0; k < s.phases.size(); k++) {
		const Trajectory &tr = s.phases[k].traj;
		const hylo_mode mode = s.modes[k];
		const hylo_mode_desc &d = mode_desc(mode);
		if (!d.planar && !d.air) {
			t0 += s.phases[k].T;
			continue;   // no hazards (the double integrator's phase plane)
		}
		auto measure = [&](hylo_point p, double t) {
			if (!d.air)
				p.z = 0;
			c.points++;
			const double d = hylo_hazard_distance(m.get(), mode, p, reach) - body_radius_m;
			if (d < c.min_clearance_m || c.phase < 0) {
				c.min_clearance_m = std::min(d, c.min_clearance_m);
				c.phase = static_cast<int>(k);
				c.mode = mode;
				c.t_s = t0 + t;
				c.x_m = p.x;
				c.y_m = p.y;
				c.z_m = p.z;
			}
			if (c.outside_phase < 0 && !in_domain(m.get(), mode, p)) {
				c.outside_phase = static_cast<int>(k);
				c.outside_t_s = t0 + t;
				c.outside_x_m = p.x;
				c.outside_y_m = p.y;
				c.outside_z_m = p.z;
			}
		};
		const size_t n = tr.t.size(), nx = static_cast<size_t>(tr.nx);
		for (size_t i = 0; i < n; i++) {
			const Motion a = motion(d, &tr.x[i * nx]);
			measure({a.p[0], a.p[1], a.p[2]}, tr.t[i]);
			if (i + 1 == n)
				break;
			const Motion b = motion(d, &tr.x[(i + 1) * nx]);
			const double h = tr.t[i + 1] - tr.t[i];
			for (int j = 1; j <= between_knots; j++) {
				const double f = static_cast<double>(j) / (between_knots + 1);
				measure(between(a, b, h, f), tr.t[i] + f * h);
			}
		}
		t0 += s.phases[k].T;
	}
	c.safe = c.outside_phase < 0 && !(c.min_clearance_m < margin_m - kCheckToleranceM);
	return c;
}

std::string ClearanceCheck::text() const
{
	char buf[320];
	if (phase < 0)
		return "no hazards to keep clear of";
	if (outside_phase >= 0) {
		std::snprintf(buf, sizeof buf, "not safe: phase %d leaves its domain at t = %.3g s, (%.3g, %.3g, %.3g) m",
			      outside_phase, outside_t_s, outside_x_m, outside_y_m, outside_z_m);
		return buf;
	}
	if (min_clearance_m >= margin_m + kClearanceReachM) {
		std::snprintf(buf, sizeof buf, "clearance over %.3g m everywhere (no hazard nearer)", min_clearance_m);
		return buf;
	}
	std::snprintf(buf, sizeof buf, "%sclearance %.3g m %s margin %.3g m (phase %d, %s, t = %.3g s at (%.3g, %.3g, %.3g) m)",
		      safe ? "" : "not safe: ", min_clearance_m, safe ? ">=" : "<", margin_m, phase, hylo_mode_str(mode), t_s,
		      x_m, y_m, z_m);
	return buf;
}

}  // namespace hylo::trainer
