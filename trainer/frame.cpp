#include "trainer/frame.hpp"

#include <cmath>

#include "trainer/modes.hpp"

namespace hylo::trainer {

Frame start_frame(hylo_mode mode, const double *x1s)
{
	Frame f;
	f.layout = mode_desc(mode).layout;
	if (f.layout == HYLO_LAYOUT_PLANAR) {   // (px, py, vx, theta)
		f.p[0] = x1s[0], f.p[1] = x1s[1], f.theta = x1s[3];
	} else if (f.layout == HYLO_LAYOUT_SPATIAL) {   // (px, py, pz, vx, vy, vz)
		f.p[0] = x1s[0], f.p[1] = x1s[1], f.p[2] = x1s[2];
	}
	return f;
}

void sampled_into_frame(const Frame &f, double *xs)
{
	if (f.layout == HYLO_LAYOUT_PLANAR) {   // moved, then turned by -theta
		const double c = std::cos(f.theta), s = std::sin(f.theta), dx = xs[0] - f.p[0], dy = xs[1] - f.p[1];
		xs[0] = c * dx + s * dy;
		xs[1] = -s * dx + c * dy;
		xs[3] -= f.theta;   // the speed is the surge, the body's own
	} else if (f.layout == HYLO_LAYOUT_SPATIAL) {
		for (int k = 0; k < 3; k++)
			xs[k] -= f.p[k];
	}
}

void full_out_of_frame(const Frame &f, std::vector<double> &x)
{
	if (f.layout == HYLO_LAYOUT_PLANAR) {   // turned by theta, then moved
		const double c = std::cos(f.theta), s = std::sin(f.theta), px = x[0], py = x[1];
		x[0] = f.p[0] + (c * px - s * py);
		x[1] = f.p[1] + (s * px + c * py);
		x[4] += f.theta;   // body-frame velocities stay
	} else if (f.layout == HYLO_LAYOUT_SPATIAL) {
		for (int k = 0; k < 3; k++)
			x[k] += f.p[k];
	}
}

}  // namespace hylo::trainer
