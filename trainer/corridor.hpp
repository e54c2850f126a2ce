// Safe corridors for the smoother (docs/smoothing.md, "Clearance"): each
// phase's position kept, piece by piece of its guess path, in axis-aligned
// boxes of cells that keep the robot's body and margin clear of its mode's
// hazards. The cell test is the onboard one (hylo_map_inflate,
// onboard/include/hylo/clearance.h): a ground (marine) box is made of clear
// GROUND (WATER) cells; a flight box spans the cells' x and y and, in z, the
// highest flight floor over them to the ceiling less the clearance.
#ifndef HYLO_TRAINER_CORRIDOR_HPP
#define HYLO_TRAINER_CORRIDOR_HPP

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "hylo/map.h"
#include "trainer/problem.hpp"
#include "trainer/terrain_grid.hpp"

namespace hylo::trainer {

// A map with its domains shrunk to the points that keep clearance r from
// every hazard, cell by cell (the onboard hylo_map_inflate).
class ClearanceMap {
public:
	// Throws std::invalid_argument for a map the onboard code refuses (too
	// many cells, bad sizes) or r not finite and >= 0.
	ClearanceMap(const TerrainGrid &grid, double r);
	~ClearanceMap();
	ClearanceMap(const ClearanceMap &) = delete;
	ClearanceMap &operator=(const ClearanceMap &) = delete;

	double clearance() const { return r_; }
	int nx() const { return nx_; }
	int ny() const { return ny_; }
	// Cell (ix, iy) is in the shrunk ground (marine) domain.
	bool clear(hylo_mode mode, int ix, int iy) const;
	// The lowest height a flight may have over cell (ix, iy) (infinity: none);
	// the highest anywhere.
	double flight_floor(int ix, int iy) const;
	double flight_top() const;

private:
	std::unique_ptr<hylo_map> m_;
	double r_ = 0;
	int nx_ = 0, ny_ = 0;
};

// The clearances the corridor builder tries, in order: the body and margin
// plus a pad (the cubic between knots may bulge a little), the body and
// margin, then only the domain itself (0).
class CorridorMaps {
public:
	CorridorMaps(const TerrainGrid &grid, double body_and_margin, double pad);
	const TerrainGrid &grid() const { return grid_; }
	const std::vector<std::unique_ptr<ClearanceMap>> &levels() const { return levels_; }

private:
	const TerrainGrid &grid_;
	std::vector<std::unique_ptr<ClearanceMap>> levels_;
};

struct Corridor {
	std::vector<CorridorBox> boxes;   // in the order of the path, timed by its arc length
	// Pieces of the path that got a box of less clearance than the first
	// level's, a lifted box, or none ("(3.5, 2) -> (5, 2): cells clear by
	// 0 m, not 0.47 m").
	std::vector<std::string> notes;
	bool first_box = false, last_box = false;   // the path's first (last) piece has a box
};

// The corridor of a phase of a planar or air mode (ground, marine, flight) along the
// polyline path (positions; z used by flight only). Each segment gets the
// box of cells around it grown greedily a row or column at a time while it
// stays clear, at the first level where its cells are clear; a segment
// whose cells are not is halved (down to a quarter cell) and its halves
// tried; a flight piece still too low is lifted (its box starts at the
// highest floor of its cells); else the next level. Consecutive pieces
// whose joint box grows clear become one. A box holds over its piece's
// share of the path's arc length, handing over to the next box in the
// middle of the stretch of path both hold, where the knots are bounded to
// both (5 cm to 0.5 m each way).
Corridor build_corridor(hylo_mode mode, const std::vector<std::array<double, 3>> &path,
			const CorridorMaps &maps);

}  // namespace hylo::trainer

#endif
