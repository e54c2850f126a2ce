// The frame a mode's dataset draws pairs in, at a pair's start: a ground or
// marine start at the origin facing +x, a flight start at the origin (its
// velocities are the world's); the double integrator's phase plane is
// absolute. The optimal cost is invariant to these moves (docs/models.md
// section 7), so the memory (memory.hpp) finds a pair's neighbours among
// the dataset's rows in this frame and moves their paths back out of it.
#ifndef HYLO_TRAINER_FRAME_HPP
#define HYLO_TRAINER_FRAME_HPP

#include <vector>

#include "hylo/modes.h"

namespace hylo::trainer {

struct Frame {
	hylo_layout_kind layout = HYLO_LAYOUT_NONE;
	double p[3] = {0, 0, 0};   // the start's position (planar: px, py)
	double theta = 0;          // planar: the start's heading
};

// The frame of a pair starting at x1s (sampled coordinates).
Frame start_frame(hylo_mode mode, const double *x1s);

// Sampled coordinates xs (docs/models.md section 7 order) into the frame.
void sampled_into_frame(const Frame &f, double *xs);

// A full state (trainer/models.hpp: planar (px, py, vx, vy, theta, ...)
// with body-frame velocities, spatial beginning with the position) out of
// the frame.
void full_out_of_frame(const Frame &f, std::vector<double> &x);

}  // namespace hylo::trainer

#endif
