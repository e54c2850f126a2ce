/*
 * hylo onboard planner: the public API.
 *
 *   hylo_planner_config cfg = { robots, n_robots, clock, clock_ctx }; // margin_m 0: the default
 *   size_t n = hylo_planner_size(&cfg);  // bytes for these robots' models
 *   hylo_planner *pl = malloc(n);        // once, at start-up (or static storage)
 *   hylo_planner_init(pl, n, &cfg);
 *   hylo_planner_set_map(pl, &map);      // each new map
 *   hylo_planner_plan(pl, &goal, &plan); // each goal; reuses the roadmap and
 *                                        // the edge costs of earlier goals
 *
 * The workspace holds every array the planner uses: the struct (capacities
 * are the compile-time constants of hylo/config.h) followed by the SVR
 * evaluators' memory, sized by the largest robot's models. No function here
 * allocates, recurses or touches the OS (time comes from an optional clock
 * callback). Not thread-safe: one planner per thread.
 */
#ifndef HYLO_PLANNER_H
#define HYLO_PLANNER_H

#include <stddef.h>
#include <stdint.h>
#include "hylo/clearance.h"
#include "hylo/config.h"
#include "hylo/map.h"
#include "hylo/robot.h"
#include "hylo/sampling.h"
#include "hylo/status.h"
#include "hylo/svr.h"
#include "hylo/types.h"
/* The workspace's layout only: struct hylo_planner embeds these modules'
 * types. Not part of the API (hylo/internal/, docs/install.md). */
#include "hylo/internal/edgecache.h"
#include "hylo/internal/roadmap.h"
#include "hylo/internal/search.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
	HYLO_ASTAR = 0,      /* values as goal_t.ALGORITHM_* */
	HYLO_DIJKSTRA = 1
} hylo_algorithm;

/* A planning request; the caller's view of a decoded goal_t. */
typedef struct {
	int64_t request_id;
	int64_t map_id;                 /* 0: the current map */
	int algorithm;                  /* hylo_algorithm */
	int start_mode;                 /* hylo_mode */
	hylo_real start[HYLO_XS_DIM];   /* sampled coordinates */
	int goal_mode;
	hylo_real goal[HYLO_XS_DIM];
	hylo_sampling sampling;         /* shapes the roadmap (hylo/sampling.h) */
	hylo_real time_budget_ms;       /* 0: no limit (needs a clock otherwise) */
	uint64_t max_expansions;        /* 0: no limit */
	hylo_real suboptimality;        /* w >= 1: a plan costing at most w times the
	                                 * optimum will do (weighted A*); 0 or 1: the optimum */
	uint32_t alternatives;          /* K <= HYLO_MAX_ALTERNATIVES: also the best paths of the
	                                 * next cheapest distinct mode sequences, up to K in all
	                                 * (hylo_planner_alternative); 0 or 1: the best plan only */
	hylo_real alternatives_within;  /* only those costing at most this times the best
	                                 * (>= 1; 0: HYLO_ALTERNATIVES_WITHIN) */
} hylo_goal;

/* The answer to one goal. status says whether the request was valid;
 * when it is HYLO_OK, outcome says what the search found: HYLO_FOUND (the
 * optimum, or at most suboptimality times it), HYLO_FOUND_UNPROVEN (the
 * budget ran out: the best complete plan found, lower_bound says how good
 * it is when known), HYLO_NO_PATH or HYLO_BUDGET_EXHAUSTED (no plan). */
typedef struct {
	hylo_status status;
	hylo_outcome outcome;
	hylo_reason reason;
	int64_t request_id;
	int64_t map_id;
	char robot[HYLO_NAME_LEN];
	hylo_real total_cost;           /* predicted energy [J] */
	hylo_real suboptimality;        /* w the plan was made with: total_cost <= w * optimum */
	hylo_real lower_bound;          /* a lower bound of the optimum [J], 0 when unknown */
	uint32_t n_waypoints;
	uint8_t mode[HYLO_MAX_WAYPOINTS];
	hylo_real state[HYLO_MAX_WAYPOINTS][HYLO_XS_DIM];
	hylo_real cost[HYLO_MAX_WAYPOINTS];   /* cumulative [J] */
	uint8_t guard[HYLO_MAX_WAYPOINTS];    /* 1: a mode switch happens here */
	uint32_t n_modes;
	uint8_t mode_sequence[HYLO_MAX_WAYPOINTS];
	/* The best path of each of the n_alternatives cheapest distinct mode
	 * sequences, cheapest first; the first is this plan (n_alternatives is 1
	 * when the goal asked for one). A sequence is the modes of the stretches
	 * the path travels (switching to and fro at one guard travels nothing),
	 * known by its number of changes; those with max_switches or more count
	 * as one (HYLO_MAX_SWITCH_LAYERS and HYLO_MAX_NODES bound it).
	 * Waypoints: hylo_planner_alternative(). */
	uint32_t n_alternatives;
	hylo_real alternative_cost[HYLO_MAX_ALTERNATIVES];       /* predicted [J] */
	uint32_t alternative_switches[HYLO_MAX_ALTERNATIVES];    /* changes of travel mode on it */
	uint32_t max_switches;
	/* statistics */
	uint32_t n_nodes;
	uint64_t n_edges;
	uint64_t n_edges_evaluated;     /* edge costs computed for this goal */
	uint64_t n_edges_cached;        /* edge costs found in the cache (earlier goals, same roadmap) */
	uint64_t n_expansions;
	uint64_t n_clamped;             /* costs raised to the floor (negative ones included) */
	uint64_t n_negative;            /* of those, predictions below 0 */
	uint64_t n_infeasible;          /* edges dropped by a feasibility classifier */
	uint64_t n_untrained;           /* edges evaluated outside their model's trained region
	                                 * (hylo/region.h): 0, as start, goal and grids are checked */
	int roadmap_reused;             /* 1: the roadmap of the previous goal was reused */
	double plan_ms;                 /* 0 without a clock */
} hylo_plan;

/* hylo_planner_config.margin_m: the body's radius alone, no margin. */
#define HYLO_NO_MARGIN (-1.0)

typedef struct {
	const hylo_robot *robots;       /* the robots this planner serves */
	uint32_t n_robots;              /* <= HYLO_MAX_ROBOTS */
	hylo_clock_fn clock;            /* optional monotonic clock [ms] */
	void *clock_ctx;
	/* The clearance every plan keeps beyond the robot's body from the
	 * hazards of its mode [m] (docs/planner.md, "Body and margin"):
	 * 0, as in a zero-initialised config, is HYLO_DEFAULT_MARGIN_M; a
	 * finite value > 0 is that margin; HYLO_NO_MARGIN keeps the body alone. */
	hylo_real margin_m;
} hylo_planner_config;

/* The workspace's head. Its fields are private; it is visible so that the
 * caller can place it: hylo_planner_size() bytes (static storage, or one
 * allocation at start-up); the SVR caches' memory follows the struct. */
typedef struct {
	hylo_planner_config cfg;
	hylo_robot robots[HYLO_MAX_ROBOTS];
	int initialized;
	int has_map;
	int64_t map_generation;         /* bumps at every set_map */
	const hylo_robot *robot;        /* robot of the current map */
	hylo_reason reason;             /* reason of the last failure */
	hylo_status map_status;         /* outcome of the last set_map; HYLO_E_NO_MAP before any */
	hylo_reason map_reason;         /* why that map was refused */
	hylo_map map;
	hylo_roadmap roadmap;
	hylo_roadmap_ws build_ws;
	hylo_search search;
	hylo_edge_cache cache;          /* costs evaluated on this roadmap */
	hylo_svr_cache svr_cache[2];    /* one per mode of the robot */
	hylo_svr_cache feas_cache[2];   /* the same for the feasibility classifiers */
	hylo_real feas_d[HYLO_MAX_COMBOS];
	/* the current request */
	uint32_t start_pos, goal_pos;   /* position ids of start and goal */
	hylo_real start_xs[HYLO_XS_DIM], goal_xs[HYLO_XS_DIM];
	uint32_t n_start_adj, n_goal_adj;
	uint32_t start_adj[HYLO_MAX_SUCCESSORS];
	uint32_t goal_adj[HYLO_MAX_SUCCESSORS];
	int start_goal_linked;          /* a direct start -> goal edge exists */
	uint8_t links_goal[HYLO_MAX_POSITIONS];
	uint8_t links_start[HYLO_MAX_POSITIONS];
	/* the heuristic: a lower bound of each node's cost to the goal, kept
	 * while the roadmap and the goal stay (planner_heuristic.c) */
	hylo_real h_node[HYLO_MAX_NODES];
	hylo_real h_radius;             /* exact up to here, this beyond */
	hylo_real h_reach;              /* h_radius >= h_reach * the start's distance */
	int h_valid;
	uint8_t h_goal_mode;
	hylo_real h_goal_xs[HYLO_XS_DIM];
	hylo_real weight;               /* the goal's suboptimality w */
	/* the edge bounds' tables (planner_graph.c): the envelope's speed nodes
	 * of each combination of each mode, the heading grid's changes */
	uint32_t combo_speed[2][HYLO_MAX_COMBOS][2];
	uint8_t combo_speed_ok[2][HYLO_MAX_COMBOS];
	hylo_real heading_change[HYLO_MAX_GRID][HYLO_MAX_GRID];
	/* each air combination's velocity heading, and whether it moves */
	hylo_real air_heading[HYLO_MAX_COMBOS];
	uint8_t air_moving[HYLO_MAX_COMBOS];
	/* the envelope's turn cell of the edges into each roadmap position from
	 * each neighbour, per heading pair: adjacency entry a's at pair_turn[a *
	 * pair_turn_stride], kept with the roadmap (0: it does not fit) */
	uint8_t pair_turn[HYLO_MAX_PAIR_TURNS];
	uint32_t pair_turn_stride;
	/* scratch of one evaluation (the combinations of one position) */
	hylo_real head_xs[HYLO_MAX_COMBOS][HYLO_XS_DIM];
	hylo_real features[HYLO_MAX_COMBOS * HYLO_MAX_FEATURES];
	uint32_t path[HYLO_MAX_WAYPOINTS];
	hylo_real path_cost[HYLO_MAX_WAYPOINTS];
	uint64_t n_clamped, n_negative, n_infeasible, n_untrained, n_evaluated, n_cached;
	int heuristic_pass;             /* 1 while computing h_pos */
	int use_heuristic;
	/* A*'s upper bound (a greedy walk's path cost) and its path */
	hylo_real bound;
	uint32_t walk_len;
	uint32_t walk_path[HYLO_MAX_WAYPOINTS];
	hylo_real walk_cost[HYLO_MAX_WAYPOINTS];
	uint32_t walk_heads[HYLO_MAX_SUCCESSORS];
	hylo_real walk_costs[HYLO_MAX_SUCCESSORS];
	/* scratch of one group's evaluation */
	uint32_t eval_idx[HYLO_MAX_COMBOS];
	/* alternatives: the search runs over `layers` copies of the graph of
	 * layer_stride nodes each (1 copy: the graph itself); the goal copies it
	 * closed, cheapest first, stay until the next goal or map */
	uint32_t layers, layer_stride;
	uint8_t layer_mode[2];          /* travel mode of even and odd layers */
	/* the layered heuristic (planner_heuristic.c): in h_node once h_layered */
	hylo_search layer_search;       /* its backward searches */
	hylo_search forward_search;     /* its forward search, resumed as the cap grows */
	int forward_begun;              /* forward_search belongs to this goal */
	uint32_t n_live;                /* layers 0 .. n_live - 1 can still reach an open goal copy */
	hylo_real h_forward[HYLO_MAX_NODES]; /* every node copy's bound-distance from the start, or less */
	const hylo_search *layered_forward;  /* while it runs: the alternatives' search */
	hylo_real layered_cap;          /* paths dearer than this are not wanted */
	hylo_real cap, cap_step;        /* the cap of h_node (layered_cap without rounding room), its last step */
	hylo_real layered_within;       /* the goal's alternatives_within */
	double deadline;                /* the goal's, on the planner's clock [ms]; +inf: none */
	int h_layered;                  /* h_node holds the layered heuristic (indexed by copy) */
	uint32_t n_found;
	uint32_t found[HYLO_MAX_ALTERNATIVES];
} hylo_planner;

/**
 * Bytes a workspace for the robots of cfg needs: sizeof(hylo_planner) plus
 * the SVR caches of the robot whose models need the most. Does not allocate.
 */
size_t hylo_planner_size(const hylo_planner_config *cfg);

/**
 * The margin cfg plans with [m]: margin_m with 0 read as
 * HYLO_DEFAULT_MARGIN_M and HYLO_NO_MARGIN as 0; -1 when margin_m is
 * neither of those nor finite and > 0 (hylo_planner_init refuses it).
 */
hylo_real hylo_planner_margin(const hylo_planner_config *cfg);

/**
 * Prepares the workspace pl of size bytes (aligned for double) for the given
 * robots (copied). Errors: HYLO_E_NULL, HYLO_E_CAP_ROBOTS, HYLO_E_CAP_SV
 * (size is less than hylo_planner_size(cfg); the reason names the largest
 * model), HYLO_E_BAD_VALUE (margin_m), and hylo_robot_check's errors. Does
 * not allocate.
 */
hylo_status hylo_planner_init(hylo_planner *pl, size_t size, const hylo_planner_config *cfg);

/**
 * Ingests a map (copied; the view may be freed afterwards) and invalidates
 * the roadmap. The domains the planner samples and connects in keep the
 * clearance of the map's robot, its body radius plus the margin
 * (hylo_planner_clearance), from every hazard (hylo_map_inflate): every
 * node, guard point and edge of a plan does. Errors: those of
 * hylo_map_ingest, HYLO_E_UNKNOWN_ROBOT, HYLO_E_EMPTY_DOMAIN (no cell of any
 * of the robot's modes, or none that keeps the clearance). On error the
 * planner has no map, and plans answer with this error's status and a
 * reason "map N was refused: ..." until the next map. O(cells times the
 * cells within the clearance of one); no allocation.
 */
hylo_status hylo_planner_set_map(hylo_planner *pl, const hylo_map_view *map);

/** The clearance the current map's plans keep [m]: the robot's body radius
 * plus the margin; 0 without a map. */
hylo_real hylo_planner_clearance(const hylo_planner *pl);

/**
 * Plans for goal on the current map: (re)builds the roadmap when the
 * sampling options changed, connects start and goal, searches, extracts the
 * path. Always fills plan (status, outcome, reason). Returns plan->status:
 * HYLO_OK when the search ran (plan->outcome: found, no path, budget
 * exhausted), otherwise HYLO_E_NO_MAP, HYLO_E_BAD_VALUE (NaN, bad options),
 * HYLO_E_MAP_MISMATCH (a map_id naming a replaced map), HYLO_E_WRONG_MODE,
 * HYLO_E_OUTSIDE_DOMAIN (also a start or goal in its mode's domain that
 * lacks the clearance: the reason names the point, the distance it keeps
 * and the clearance it needs), HYLO_E_CAP_*, HYLO_E_BAD_COST. No allocation.
 */
hylo_status hylo_planner_plan(hylo_planner *pl, const hylo_goal *goal, hylo_plan *plan);

/**
 * Alternative k (0: the plan itself) of the last hylo_planner_plan, cheapest
 * first, into plan's path fields (total_cost, waypoints, modes, mode
 * sequence); its other fields are left as they are. Valid until the next
 * plan or map. Errors: HYLO_E_NULL, HYLO_E_BAD_VALUE (k >= the last plan's
 * n_alternatives). No allocation.
 */
hylo_status hylo_planner_alternative(hylo_planner *pl, uint32_t k, hylo_plan *plan);

/**
 * Checks the fields of goal g that need no map: algorithm and mode numbers,
 * every entry of start and goal (also those the mode does not use), every
 * spacing and radius finite and >= 0, time_budget_ms finite and >= 0,
 * suboptimality, and each sampling grid (at most HYLO_MAX_GRID finite
 * entries). hylo_planner_plan runs it first; a node may run it when a goal
 * arrives. HYLO_OK, or a status with a reason naming the field in r (may be
 * NULL). Does not allocate; safe in a control loop.
 */
hylo_status hylo_goal_check(const hylo_goal *g, hylo_reason *r);

/** The reason for the last failure ("ok" after a success). Never NULL. */
const char *hylo_planner_reason(const hylo_planner *pl);

/** The roadmap of the current map and the last goal's sampling options, or
 * NULL when none has been built (for tools that draw it). */
const hylo_roadmap *hylo_planner_roadmap(const hylo_planner *pl);

/**
 * Costs of the edges from node tail to heads[0 .. n) of the last goal's
 * graph (roadmap nodes, then start rm->n_nodes and goal rm->n_nodes + 1),
 * with the weights the search uses: the model's prediction raised to the
 * edge's lower bound, +inf where the feasibility classifier drops the edge,
 * the switch cost on a switch edge. Every head must be a successor of tail
 * (HYLO_E_BAD_VALUE otherwise). Does not use or fill the cache; no
 * allocation. For references and tests (an exhaustive search).
 */
hylo_status hylo_planner_edge_costs(hylo_planner *pl, uint32_t tail, const uint32_t *heads,
                                    uint32_t n, hylo_real *costs);

/**
 * The successors of node tail in the last goal's graph into heads (capacity
 * HYLO_MAX_SUCCESSORS), their number into *n, with nothing pruned. For
 * references and tests. No allocation.
 */
hylo_status hylo_planner_successors(hylo_planner *pl, uint32_t tail, uint32_t *heads, uint32_t *n);

#ifdef __cplusplus
}
#endif

#endif
