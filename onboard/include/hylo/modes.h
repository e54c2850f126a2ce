/*
 * Each locomotion mode described once: one record per mode (its name, its
 * sampled coordinates and their units, the speed a cost model's training
 * range bounds, the displacement its max_distance_m bounds, planar or air,
 * the map cells that are its domain, its SVR features and their groups, the
 * trainer's state and input sizes). The onboard library, the trainer and
 * the tools read them here; tools/hylo_client.py carries a generated copy
 * of the names (tests/node/client_tables.c checks it). A new mode is one
 * more record in onboard/src/modes.c, plus its value in hylo_mode
 * (types.h, the value of goal_t.MODE_*) and its dynamics in the trainer
 * (trainer/models.hpp).
 */
#ifndef HYLO_MODES_H
#define HYLO_MODES_H

#include <stddef.h>
#include <stdint.h>
#include "hylo/config.h"
#include "hylo/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which SVR features a mode's edges have (hylo/features.h). A model's
 * features are those of one layout; the layouts' feature counts differ, so
 * a model's n_features names its layout (hylo_feature_layout_of_count). */
typedef enum {
	HYLO_LAYOUT_NONE = 0,
	HYLO_LAYOUT_PLANAR = 1,   /* (px, py, vx, theta): 5 relative coordinates, 8 features */
	HYLO_LAYOUT_SPATIAL = 2,  /* (px, py, pz, vx, vy, vz): 9, taken in the horizontal heading */
	HYLO_LAYOUT_PHASE = 3,    /* (p, v), absolute, and the prior: 5 */
	HYLO_LAYOUT_COUNT = 4
} hylo_layout_kind;

/* A feature layout: its sizes and the feature groups of the SVR batch
 * evaluator (hylo/svr.h, "Batch evaluation"): group g holds the features
 * order[begin[g] .. begin[g + 1]), the groups in product order (tail
 * first, then the head's pose, then its speed). */
typedef struct {
	hylo_layout_kind kind;
	const char *name;             /* "planar", "spatial", "phase" */
	uint8_t n_relative;           /* relative coordinates (hylo_relative) */
	uint8_t n_features;           /* features (hylo_features), <= HYLO_MAX_FEATURES */
	uint8_t n_groups;
	uint8_t order[HYLO_MAX_FEATURES];
	uint8_t begin[HYLO_MAX_FEATURES + 1];
	uint8_t envelope;             /* 1: models of this layout may carry an envelope ... */
	uint8_t envelope_turn;        /* ... whose z cells are turns (1) or climbs (0) */
} hylo_feature_layout;

/* The cells of the map that are a mode's domain (hylo_domain_contains). */
typedef enum {
	HYLO_DOMAIN_NONE = 0,
	HYLO_DOMAIN_LAND = 1,    /* GROUND cells (clear of the inflated hazards) */
	HYLO_DOMAIN_WATER = 2,   /* WATER cells (likewise) */
	HYLO_DOMAIN_AIR = 3,     /* above every touching cell's flight floor, below the ceiling */
	HYLO_DOMAIN_PHASE = 4    /* non-obstacle cells of the phase plane, on the mode's side of p = 0 */
} hylo_domain_kind;

typedef struct {
	const char *name, *unit;
} hylo_coord_desc;

typedef struct {
	hylo_mode mode;
	const char *name;             /* "ground": lower case, the goal_t/scene/CLI spelling */
	const char *c_name;           /* "HYLO_MODE_GROUND": the enum constant, as headers write it */
	uint8_t xs_dim;               /* sampled coordinates x^s, <= HYLO_XS_DIM */
	hylo_coord_desc coord[HYLO_XS_DIM];
	/* hylo_state_speed: coordinate speed_index (signed) when speed_width
	 * is 1, else the norm of coordinates speed_index .. + speed_width. */
	uint8_t speed_index, speed_width;
	uint8_t distance_dims;        /* hylo_edge_distance: the norm of the first ones' change */
	uint8_t planar;               /* x^s = (px, py, vx, theta): a heading on a surface */
	uint8_t air;                  /* airborne: 3-D positions, the air spacing and radius */
	hylo_domain_kind domain;
	int8_t side;                  /* HYLO_DOMAIN_PHASE: -1 p <= 0, +1 p >= 0 */
	uint8_t damped;               /* double integrator: v' = u - v, else v' = u (the trainer's dynamics, the features' prior) */
	hylo_layout_kind layout;
	uint8_t nx, nu;               /* the trainer's full state and input (trainer/models.hpp) */
} hylo_mode_desc;

/** The record of mode, or NULL for HYLO_MODE_NONE or an invalid value. */
const hylo_mode_desc *hylo_mode_describe(hylo_mode mode);

/** The mode named name ("ground", ...), or HYLO_MODE_NONE. */
hylo_mode hylo_mode_parse(const char *name);

/** Writes the modes' names, ", "-separated in enum order, into out (at
 * most n bytes, NUL-terminated) and returns out: for messages that list
 * the modes. */
char *hylo_mode_names(char *out, size_t n);

/** The kind of mode's domain; HYLO_DOMAIN_NONE for an invalid mode. */
hylo_domain_kind hylo_mode_domain(hylo_mode mode);

/** The layout of kind, or NULL. */
const hylo_feature_layout *hylo_feature_layout_of(hylo_layout_kind kind);

/** The layout of mode's features, or NULL for an invalid mode. */
const hylo_feature_layout *hylo_mode_layout(hylo_mode mode);

/** The layout whose feature count is n_features, or NULL: how the SVR
 * evaluator knows a model's feature groups (hylo_svr_model carries its
 * feature count; its header's HYLO_MODEL_<NAME>_MODE names its mode). */
const hylo_feature_layout *hylo_feature_layout_of_count(uint32_t n_features);

#ifdef __cplusplus
}
#endif

#endif
