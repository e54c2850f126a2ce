/*
 * The planner's parts, shared between planner.c (requests, validation,
 * plans), planner_graph.c (edge costs and the search's callbacks) and
 * planner_heuristic.c (the A* heuristic). Not a public header.
 *
 * The search graph is implicit: a node is (position, combination); its
 * successors are every combination of every neighbouring position of the
 * same mode, the guard twin's switch edges, and the goal when it is in
 * reach. Positions rm->n_positions and rm->n_positions + 1 are the start and
 * the goal, with one node each (rm->n_nodes, rm->n_nodes + 1).
 */
#ifndef HYLO_PLANNER_INTERNAL_H
#define HYLO_PLANNER_INTERNAL_H

#include "hylo/planner.h"

/* The group number of the edge into the goal (the others are a neighbour's
 * index in the tail position's list). */
#define HYLO_GOAL_GROUP (UINT32_MAX - 1u)

/* The model of mode for the current map's robot. */
const hylo_mode_model *hylo_planner_mode_model(const hylo_planner *pl, hylo_mode mode);

/* Sampled coordinates of combination c of position i (start and goal included). */
void hylo_planner_node_state(const hylo_planner *pl, uint32_t i, uint32_t c, hylo_real *xs);

/* The neighbours of position i whose nodes lead to it (i's own list; the
 * start's from the request), into *n. */
const uint32_t *hylo_planner_neighbours(const hylo_planner *pl, uint32_t i, uint32_t *n);

/*
 * Edge bounds. The bound of an edge from a state at position i to a state
 * at position j (same mode) is the model's floor for the distance, raised to
 * its envelope for the edge: the same value hylo_envelope_of_edge gives,
 * computed from what the pair of positions shares (distance, climb,
 * bearing) so that the heuristic's pass over every edge stays cheap. Edge
 * costs are raised to it, so it holds for every edge, and the heuristic
 * built from it is consistent.
 */
typedef struct {
	const hylo_planner *pl;
	hylo_real floor;                /* the model's floor for the distance [J] */
	const hylo_svr_model *model;    /* with an envelope, else NULL */
	hylo_mode mode;
	int slot;                       /* the mode's index in the robot */
	hylo_real dx, dy;               /* displacement */
	hylo_real d, dz, phi;           /* horizontal distance, climb, bearing */
	int roadmap_ends;               /* both positions sampled (not start or goal) */
	int by_turn;                    /* planar, turn cells: a cell per heading pair */
	int cell_ok;                    /* else: the pair's one cell */
	int by_flight_turn;             /* flight with a turn table, positions apart */
	int flight_turn_base_ok;        /* by flight turn, roadmap ends: the next two */
	size_t flight_turn_base;        /* the turn table's cell of the distance, turn 0 */
	hylo_real air_off[HYLO_MAX_COMBOS];  /* |wrap(heading - phi)| per air combination, 0 still */
	size_t cell;
	hylo_real bearing[HYLO_MAX_GRID];   /* wrap(phi - heading) per grid heading */
	size_t turn_base;               /* by turn: the distance's first turn cell */
	int turn_base_ok;
	const uint8_t *turn_cells;      /* cached turn cell per heading pair, or NULL */
} hylo_pair_bound;

void hylo_planner_pair_bound(const hylo_planner *pl, uint32_t i, uint32_t j, hylo_pair_bound *pb);

/* The same for the edges from neighbour i into roadmap position j, the
 * pair at adjacency entry a of j's list, with their turn cells from
 * pl->pair_turn (computed there the first time): the same bounds. */
void hylo_planner_pair_bound_into(hylo_planner *pl, uint32_t i, uint32_t j, uint32_t a,
				  hylo_pair_bound *pb);

/* The same for the edges from position i to j, its neighbour k in
 * hylo_planner_neighbours (HYLO_GOAL_GROUP: the goal), with the turn cells
 * cached under j's entry naming i when there is one. */
void hylo_planner_pair_bound_to(hylo_planner *pl, uint32_t i, uint32_t k, uint32_t j,
				hylo_pair_bound *pb);

/* The least bound of any edge from position i to j: its mode's floor for
 * their distance (every bound is at least that). */
hylo_real hylo_planner_pair_floor(const hylo_planner *pl, uint32_t i, uint32_t j);

/* The bound of the edge from combination ci (state tail) of the pair's
 * first position to combination cj (state head) of its second. */
hylo_real hylo_planner_bound(const hylo_pair_bound *pb, uint32_t ci, const hylo_real *tail,
			     uint32_t cj, const hylo_real *head);

/* The bounds of every edge from combination ci (state tail) of the pair's
 * first position to the combinations of its second, j, into out[], and of
 * every edge from the combinations of its first, i, into combination cj
 * (state head) of its second: hylo_planner_bound()'s numbers. */
void hylo_planner_bounds_from(const hylo_pair_bound *pb, uint32_t ci, const hylo_real *tail,
			      uint32_t j, hylo_real *out);
void hylo_planner_bounds_into(const hylo_pair_bound *pb, uint32_t i, uint32_t cj,
			      const hylo_real *head, hylo_real *out);

/* Fills the planner's tables for the bounds' fast path (after a roadmap is
 * built). */
void hylo_planner_bound_tables(hylo_planner *pl);

/* Cost of the switch edges from guard copy i to its twin. */
hylo_real hylo_planner_switch_cost(const hylo_planner *pl, uint32_t i);

/* The heuristic of the search's node u (with alternatives, a graph node's
 * copy in a layer: its own value, towards the goal copies still open). */
hylo_real hylo_planner_h(const hylo_planner *pl, uint32_t u);
/* The graph node of the search's node u (alternatives search the graph's
 * copies, one per layer: hylo_planner.layers). */
uint32_t hylo_planner_graph_node(const hylo_planner *pl, uint32_t u);

/* How far past the start's distance the heuristic's backward search goes
 * for one plan; for alternatives, as far as they are sought
 * (alternatives_within, when that is further; +inf: every node). */
#define HYLO_HEURISTIC_REACH 1.25

/* Computes h_node for the current goal (planner_heuristic.c), or keeps it
 * when the roadmap and the goal are those it was computed for. */
hylo_status hylo_planner_heuristic(hylo_planner *pl, const hylo_budget *budget);

/* The alternatives' search's callbacks when it closes a goal copy (the
 * layered heuristic is computed towards the others, planner_heuristic.c)
 * and for a deferred group's key (planner_graph.c). */
hylo_status hylo_planner_found(void *ctx, hylo_search *s, uint32_t goal, int *grew,
			       hylo_reason *r);
hylo_real hylo_planner_group_key(void *ctx, hylo_search *s, uint32_t u, uint32_t group);

/* The search's callbacks (ctx: the planner). */
hylo_status hylo_planner_expand(void *ctx, hylo_search *s, uint32_t u, uint32_t *heads,
				hylo_real *costs, uint32_t cap, uint32_t *n, hylo_reason *r);
hylo_status hylo_planner_resolve(void *ctx, hylo_search *s, uint32_t u, uint32_t group,
				 uint32_t *heads, hylo_real *costs, uint32_t cap, uint32_t *n,
				 hylo_reason *r);

/* A greedy walk from the start on the heuristic: the cost of a real path
 * (an upper bound of the optimum, kept with its path in pl->walk_*), or
 * +inf when it gets stuck or passes deadline [ms, on the planner's clock]. */
hylo_real hylo_planner_greedy_walk(hylo_planner *pl, double deadline);

/* The planner's clock [ms], 0 without one. */
double hylo_planner_now(const hylo_planner *pl);

#endif
