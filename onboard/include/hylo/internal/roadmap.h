/*
 * The roadmap: sampled positions of every mode, guard twins, the
 * neighbour lists between positions (same mode, within the connection
 * radius, straight segment inside the domain), and the velocity/heading
 * combinations that turn each position into graph nodes. It depends only on
 * the map and the sampling options, so it is built once and reused for every
 * goal with the same options; only the start and goal connections change.
 *
 * Node ids: the nodes of position i are node_base[i] .. node_base[i] +
 * n_combos(i) - 1. The start and goal are two extra positions with one node
 * each, after all sampled ones.
 *
 * Internal: not part of hylo's API. Installed (hylo/internal/) only because
 * struct hylo_planner embeds this module's types; its declarations may
 * change in any release. Include "hylo/planner.h" instead.
 */
#ifndef HYLO_ROADMAP_H
#define HYLO_ROADMAP_H

#include <stdint.h>
#include "hylo/config.h"
#include "hylo/map.h"
#include "hylo/internal/poisson.h"
#include "hylo/robot.h"
#include "hylo/sampling.h"
#include "hylo/status.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
	HYLO_POS_SAMPLE = 0,   /* Poisson sample of a domain */
	HYLO_POS_GUARD = 1,    /* one copy of a guard sample; twin is the other */
	HYLO_POS_START = 2,
	HYLO_POS_GOAL = 3
} hylo_position_kind;

typedef struct {
	hylo_point p;
	uint8_t mode;          /* hylo_mode */
	uint8_t kind;          /* hylo_position_kind */
	uint16_t n_combos;     /* nodes at this position */
	uint32_t twin;         /* the guard twin's position id, or HYLO_NO_POSITION */
	uint32_t node_base;    /* first node id */
	uint32_t adj_begin;    /* neighbours: adjacency[adj_begin .. adj_end) */
	uint32_t adj_end;
} hylo_position;

#define HYLO_NO_POSITION UINT32_MAX

typedef struct {
	hylo_sampling sampling;            /* options it was built with */
	int built;                         /* 1 once built for the current map */
	uint32_t n_positions;              /* sampled + guard copies (start/goal excluded) */
	uint32_t n_nodes;                  /* nodes of those positions */
	uint64_t n_edges;                  /* directed edges among them, switch edges included */
	uint32_t max_successors;           /* largest out-degree of a node */
	uint32_t n_per_mode[HYLO_MODE_COUNT]; /* sampled positions per mode */
	uint32_t n_guards;                 /* guard samples (each has two copies) */
	uint32_t n_air_velocities;         /* flight velocity combinations */
	hylo_real air_velocity[HYLO_MAX_COMBOS][3];
	uint8_t air_class[HYLO_MAX_COMBOS];  /* index of each flight velocity's speed in air_speeds */
	hylo_position pos[HYLO_MAX_POSITIONS];
	uint32_t adjacency[HYLO_MAX_ADJACENCY];
	/* The way back: when i's entry a names j, j's entry adj_reverse[a]
	 * names i (the lists are symmetric; UINT32_MAX if not). */
	uint32_t adj_reverse[HYLO_MAX_ADJACENCY];
	uint32_t n_adjacency;
	uint32_t node_pos[HYLO_MAX_NODES]; /* position of each node */
} hylo_roadmap;

/* Scratch used while building; not needed afterwards. */
typedef struct {
	hylo_poisson_ws poisson;
	hylo_point points[HYLO_MAX_POSITIONS];
	uint32_t neighbours[HYLO_MAX_SUCCESSORS];
} hylo_roadmap_ws;

/**
 * Builds the roadmap of robot on map m with sampling options s: samples each
 * mode's domain and the guard, pairs guard copies, joins neighbours, assigns
 * node ids. Errors: HYLO_E_BAD_VALUE (options), HYLO_E_EMPTY_DOMAIN, and the
 * HYLO_E_CAP_* of positions, nodes, adjacency, combos, successors, buckets.
 * Does not allocate. O(positions * neighbours) segment checks.
 */
hylo_status hylo_roadmap_build(hylo_roadmap *rm, hylo_roadmap_ws *ws, const hylo_map *m,
                               const hylo_robot *robot, const hylo_sampling *s,
                               hylo_reason *r);

/** Number of velocity/heading combinations of a sampled position of mode. */
uint32_t hylo_roadmap_combos(const hylo_roadmap *rm, hylo_mode mode);

/**
 * Sampled coordinates of combination c at position i into xs
 * (HYLO_XS_DIM entries, unused ones 0).
 */
void hylo_roadmap_state(const hylo_roadmap *rm, uint32_t i, uint32_t c, hylo_real *xs);

/** 1 when combination c of a position of mode is at rest (speed 0): the
 * only combinations with takeoff/landing switch edges. */
int hylo_roadmap_at_rest(const hylo_roadmap *rm, hylo_mode mode, uint32_t c);

/*
 * Speed classes: the combinations of a position that share a speed (ground
 * and marine: an entry of speeds; flight: of air_speeds; the double
 * integrator: one class). The A* heuristic works on (position, class).
 */
/** Number of speed classes of a sampled position of mode (>= 1). */
uint32_t hylo_roadmap_class_count(const hylo_roadmap *rm, hylo_mode mode);

/** Speed class of combination c of a position of mode. */
uint32_t hylo_roadmap_class(const hylo_roadmap *rm, hylo_mode mode, uint32_t c);

/** Connection radius of mode under the roadmap's options. */
hylo_real hylo_roadmap_radius(const hylo_roadmap *rm, hylo_mode mode);

/**
 * Positions of mode within its connection radius of p whose straight
 * segment to p lies in the domain, in increasing id order, into out
 * (capacity HYLO_MAX_SUCCESSORS); self (or HYLO_NO_POSITION) is left out.
 * Uses the spatial grid left in ws by hylo_roadmap_build.
 */
hylo_status hylo_roadmap_neighbours(const hylo_roadmap *rm, hylo_roadmap_ws *ws,
                                    const hylo_map *m, hylo_point p, hylo_mode mode,
                                    uint32_t self, uint32_t *out, uint32_t *n,
                                    hylo_reason *r);

/**
 * Switch edges of node (position i, combination c): the combinations of i's
 * guard twin it leads to, into combos (capacity HYLO_MAX_COMBOS); returns
 * their number (0 when i is not a guard copy). Takeoff and landing join rest
 * states only; the shoreline and p = 0 keep the sampled coordinates.
 */
uint32_t hylo_roadmap_switch_heads(const hylo_roadmap *rm, uint32_t i, uint32_t c,
                                   uint32_t *combos);

/** Euclidean distance between two points [m]. */
hylo_real hylo_roadmap_distance(hylo_point a, hylo_point b);

/** 1 when the two samplings are identical (the roadmap can be reused). */
int hylo_sampling_equal(const hylo_sampling *a, const hylo_sampling *b);

/**
 * Checks s's grids as hylo_goal_check does (it calls this): each at most
 * HYLO_MAX_GRID entries (HYLO_E_CAP_GRID), every entry finite. The checks
 * that need the robot are hylo_roadmap_build's.
 */
hylo_status hylo_sampling_check_grids(const hylo_sampling *s, hylo_reason *r);

#ifdef __cplusplus
}
#endif

#endif
