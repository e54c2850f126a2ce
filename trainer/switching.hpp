// Mode switches of multi-phase problems (docs/models.md section 6): the reset map
// between consecutive phases, the guard the switch point stays on, and the
// switching cost.
//   di_pos <-> di_neg   guard p = 0, identity reset, cost 0
//   ground <-> marine   guard: the shoreline (a segment here), state carried
//                       over, phiL = phiR = phi_n(vx) entering the water, cost 0
//   ground -> flight    takeoff from rest at terrain height h to hover at h + 1
//                       (yaw 0), cost J_takeoff; guard: an area of level ground
//   flight -> ground    landing from that hover to rest with heading 0, cost J_landing
#ifndef HYLO_TRAINER_SWITCHING_HPP
#define HYLO_TRAINER_SWITCHING_HPP

#include <cstddef>
#include <string>
#include <utility>

#include "trainer/collocation.hpp"
#include "trainer/params.hpp"

namespace hylo::trainer {

// Where a switch may happen: its (px, py) on the segment a-b (a == b pins it),
// or with area set anywhere in the axis-aligned rectangle with corners a and
// b, at terrain height height_m. Unused by the double integrator (p = 0).
struct SwitchGuard {
	double ax = 0, ay = 0, bx = 0, by = 0;
	double height_m = 0;
	bool area = false;
};

// Energies of takeoff and landing [J]: the flight problems from hover at h to
// hover at h + 1 and back (translation-invariant, so any h).
struct TakeoffLanding {
	double takeoff_j = 0, landing_j = 0;
};
TakeoffLanding takeoff_landing(const RobotParams &robot, const SolveOptions &opt);

// Joins phase k to phase k + 1 of problem: reset rows, guard rows and the
// knot bounds of the switch, and adds its cost. Fills empty knot bounds of the
// two phases with their modes' bounds first. Throws std::invalid_argument for
// a pair of modes with no switch between them.
void join_phases(MultiPhaseProblem &problem, size_t k, const RobotParams &robot, const SwitchGuard &guard,
		 const TakeoffLanding &costs = {});

// A wall a flight crosses: phases k and k + 1 (both flight, one flight cut
// in two) meet on the vertical plane x = c (axis 0) or y = c (axis 1) at
// least z_min high. The state carries over unchanged; no cost.
struct WallGate {
	int axis = 0;
	double c = 0, z_min = 0;
};
void join_gate(MultiPhaseProblem &problem, size_t k, const RobotParams &robot, const WallGate &gate);

// A via point: phases k and k + 1 (one mode, one run cut in two) meet at
// position (x, y) (and height z for a flight); the state carries over; no cost.
void join_via(MultiPhaseProblem &problem, size_t k, const RobotParams &robot, const double *position);

// A phase of mode from sampled state xs0 to xs1 (either nullptr: left free
// within the mode's bounds), its guess a straight line guess0 -> guess1.
PhaseSpec phase_between(hylo_mode mode, const RobotParams &robot, const double *xs0,
			const double *xs1, const double *guess0, const double *guess1, int segments);

// The hybrid double integrator a -> (0, v) -> b (a and b on opposite sides
// of p = 0) as one two-phase problem, the switch free on p = 0, guessed
// through (0, v_guess).
MultiPhaseSolution di_two_phase(const RobotParams &di, const double *a, const double *b, double v_guess);

// Its reference optimum (the paper's Fig. 10): the least cost of the two
// single-phase problems through a fixed switch state (0, v), v swept over
// [-1, 1] every 0.05 and refined by golden-section search. {cost, v}.
std::pair<double, double> di_swept_optimum(const RobotParams &di, const double *a, const double *b);

}  // namespace hylo::trainer

#endif
