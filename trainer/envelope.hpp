// The envelope of a cost model (onboard/models/README.md, "Envelope"): per
// cell of edge distance and turn (ground, marine: hylo_envelope_turn, 16
// cells over [0, 2 pi]) or climb (flight) and pair of speed nodes, a lower
// bound of the model's predicted cost over every heading of that turn
// (ground, marine) or level velocity direction (flight), exported as a
// float table that the planner's search uses as an edge bound far tighter
// than the per-metre floor. Computed at export from the fitted model with the onboard
// evaluator itself, so the values are the planner's; deterministic (the same
// bytes for any number of jobs).
#ifndef HYLO_TRAINER_ENVELOPE_HPP
#define HYLO_TRAINER_ENVELOPE_HPP

#include <cstddef>
#include <cstdint>
#include <string>

#include "trainer/svr_export.hpp"

namespace hylo::trainer {

struct EnvelopeOptions {
	int jobs = 1;                    // threads; the table does not depend on it
	size_t check_edges = 1000000;    // random edges per measurement (margin, check)
	uint64_t margin_seed = 1;        // edges whose worst shortfall sets the margin
	uint64_t check_seed = 2;         // fresh edges the exported table must not exceed
	double min_margin = 1e-3;        // the margin is max(this, 2 x worst shortfall)
	int check_rounds = 3;            // fresh checks, the margin widened after each failed one
	bool progress = true;            // one line per stage on stdout
	bool debug = false;              // trace each stage's time and every edge below the table on stderr
};

struct EnvelopeReport {
	EnvelopeExport table;            // with the margin, rounded down to float
	double margin = 0;
	double worst_shortfall = 0;      // largest (table - cost) / cost before the margin, margin_seed edges
	size_t shortfall_edges = 0;      // margin_seed edges below the table before the margin
	size_t check_violations = 0;     // check_seed edges below the exported table (0, or it throws)
	double check_closest = 0;        // least (cost - table) / cost over the check_seed edges
	size_t sampled = 0;              // edges per measurement
	double table_seconds = 0, margin_seconds = 0, check_seconds = 0;

	// The header's provenance line: "n_d x n_z x n_v cells, margin M, worst
	// sampled shortfall S (...)".
	std::string provenance() const;
};

// Whether m gets an envelope: ground, marine and flight models with a
// training distance (max_distance_m > 0) and speed range.
bool envelope_applies(const SvrExport &m);

// The speed nodes' step for a training speed range [lo, hi]: the finest of
// 0.1, 0.25, 0.5, 1, 2.5 and 5 m/s that divides it into at most 12 equal
// steps (Ambot 0.1, Drivocopter ground 0.25, flight 1). Throws
// std::invalid_argument when none does.
double envelope_speed_step(double lo, double hi);

// Computes m's envelope (any envelope m has is ignored), measures the margin
// on opt.check_edges random edges and checks the exported table on as many
// fresh ones. Throws std::invalid_argument when m gets none
// (envelope_applies) and std::runtime_error when a fresh edge costs less
// than its cell's exported value.
EnvelopeReport compute_envelope(const SvrExport &m, const EnvelopeOptions &opt);

// Whether m gets a turn table (hylo_svr_model.turn_envelope): flight models
// that get an envelope.
bool turn_table_applies(const SvrExport &m);

// Computes m's flight turn table: per distance cell of the envelope, turn
// cell (16 over [0, 2 pi], hylo_envelope_flight_turn) and pair of the
// envelope's speed nodes, the least predicted cost over every climb within
// the training distance and every pair of level velocity directions of
// that turn; margin and check as compute_envelope's. Throws as it does
// (std::invalid_argument when turn_table_applies is false).
EnvelopeReport compute_turn_table(const SvrExport &m, const EnvelopeOptions &opt);

}  // namespace hylo::trainer

#endif
