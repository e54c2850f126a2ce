/*
 * Compile-time capacities of the onboard planner. Every one can be overridden
 * with -D; the workspace (struct hylo_planner) grows with them. Exceeding a
 * capacity at run time returns a status naming it (HYLO_E_CAP_*), never an
 * out-of-bounds write. The defaults hold every committed scene several times
 * over in about 12 MB, plus the SVR caches' memory sized by the models
 * (hylo_planner_size; docs/decisions.md, "Planner capacities").
 */
#ifndef HYLO_CONFIG_H
#define HYLO_CONFIG_H

/* Map cells, nx * ny (512 x 512). */
#ifndef HYLO_MAX_CELLS
#define HYLO_MAX_CELLS 262144
#endif

/* Sampled positions of all modes, guard copies, start and goal. */
#ifndef HYLO_MAX_POSITIONS
#define HYLO_MAX_POSITIONS 8192
#endif

/* Graph nodes: positions times their velocity/heading combinations. */
#ifndef HYLO_MAX_NODES
#define HYLO_MAX_NODES 65536
#endif

/* Position adjacency entries (an undirected neighbour pair counts twice). */
#ifndef HYLO_MAX_ADJACENCY
#define HYLO_MAX_ADJACENCY 131072
#endif

/* Bytes of the edge bounds' turn-cell cache: one byte per heading pair of
 * each adjacency entry (64 for 8 headings); a roadmap that needs more is
 * bounded without it (the same bounds, computed each time). */
#ifndef HYLO_MAX_PAIR_TURNS
#define HYLO_MAX_PAIR_TURNS 524288
#endif

/* Entries of each sampling grid (speeds, headings, flight speeds). */
#ifndef HYLO_MAX_GRID
#define HYLO_MAX_GRID 16
#endif

/* Velocity/heading combinations at one position. */
#ifndef HYLO_MAX_COMBOS
#define HYLO_MAX_COMBOS 128
#endif

/* Successors of one node, i.e. edge costs evaluated per expansion. */
#ifndef HYLO_MAX_SUCCESSORS
#define HYLO_MAX_SUCCESSORS 16384
#endif

/* Groups of successors the search may defer at once (lazy edge
 * evaluation); when full, successors are evaluated at once instead. */
#ifndef HYLO_MAX_DEFERRED
#define HYLO_MAX_DEFERRED 65536
#endif

/* The edge-cost cache (hylo/internal/edgecache.h): successor groups (a node and one
 * neighbouring position) of one roadmap, and costs kept. A roadmap with more
 * groups is planned without the cache. */
#ifndef HYLO_MAX_GROUPS
#define HYLO_MAX_GROUPS 262144
#endif
#ifndef HYLO_MAX_CACHED_COSTS
#define HYLO_MAX_CACHED_COSTS 262144
#endif

/* Alternatives (hylo_goal.alternatives): the best paths of up to this many
 * distinct mode sequences per plan. They come from one search over copies of
 * the graph, one per number of mode switches so far (0, 1, ..., then "this
 * many or more" in the last), at most HYLO_MAX_SWITCH_LAYERS copies and
 * together at most HYLO_MAX_NODES nodes; the search's goals are the goal's
 * copies. */
#ifndef HYLO_MAX_ALTERNATIVES
#define HYLO_MAX_ALTERNATIVES 8
#endif
#ifndef HYLO_MAX_SWITCH_LAYERS
#define HYLO_MAX_SWITCH_LAYERS 12
#endif
#define HYLO_MAX_SEARCH_GOALS HYLO_MAX_SWITCH_LAYERS
/* K for a goal on the bus or in a scene file whose alternatives is 0
 * (goal_t.DEFAULT_ALTERNATIVES): the graph ranks mode sequences closer than
 * its discretization error wrongly, so the smoother compares three. A
 * hylo_goal itself says what it wants: 0 or 1 is the plan only. */
#define HYLO_DEFAULT_ALTERNATIVES 3

/* The default of hylo_goal.alternatives_within: alternatives predicted
 * more than 25% dearer than the best are left out (the graph's costs are
 * 6-23% above the smoothed ones on the paper's scenes, docs/planner.md). */
#define HYLO_ALTERNATIVES_WITHIN 1.25

/* Waypoints of one plan. */
#ifndef HYLO_MAX_WAYPOINTS
#define HYLO_MAX_WAYPOINTS 4096
#endif

/* Buckets of the spatial hash grids (sampling, neighbour search). */
#ifndef HYLO_MAX_BUCKETS
#define HYLO_MAX_BUCKETS 262144
#endif

/* Support vectors of one SVR model (a sanity limit: the caches' memory is
 * sized by the loaded models), and features of one model. */
#ifndef HYLO_MAX_SV
#define HYLO_MAX_SV 65536
#endif
#ifndef HYLO_MAX_FEATURES
#define HYLO_MAX_FEATURES 9
#endif

/* Distinct values per feature group kept by the SVR batch evaluator's kernel-factor
 * cache (see svr.h). Memory per model: (groups * this + features + groups)
 * doubles per support vector (hylo_svr_cache_size). */
#ifndef HYLO_SVR_CACHE_VALUES
#define HYLO_SVR_CACHE_VALUES 8
#endif

/* Robots known to one planner, and length of names and reasons. */
#ifndef HYLO_MAX_ROBOTS
#define HYLO_MAX_ROBOTS 8
#endif
#define HYLO_NAME_LEN 32
#define HYLO_REASON_LEN 200

/* Relations the code relies on. */
typedef char hylo_check_nodes_cover_positions[(HYLO_MAX_NODES >= HYLO_MAX_POSITIONS) ? 1 : -1];
typedef char hylo_check_combos_cover_grid[(HYLO_MAX_COMBOS >= HYLO_MAX_GRID) ? 1 : -1];
typedef char hylo_check_successors_cover_combos[(HYLO_MAX_SUCCESSORS >= HYLO_MAX_COMBOS) ? 1 : -1];
typedef char hylo_check_grid_fits_u8[(HYLO_MAX_GRID <= 256) ? 1 : -1];
typedef char hylo_check_layers_cover_alternatives[(HYLO_MAX_SWITCH_LAYERS >= HYLO_MAX_ALTERNATIVES) ? 1 : -1];
typedef char hylo_check_positions_fit_u32[(HYLO_MAX_NODES < 0x7fffffffL) ? 1 : -1];

#endif
