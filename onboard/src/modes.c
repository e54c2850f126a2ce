#include "hylo/modes.h"

#include "hylo/features.h"

#include <stdio.h>
#include <string.h>

/* The feature layouts (hylo/features.h defines the features). */
static const hylo_feature_layout layouts[HYLO_LAYOUT_COUNT] = {
	/* (dx', |dy'|, s*dtheta, vx1, vx2, d, turn, arc): (vx1), the head's
	 * pose (dx', |dy'|, s*dtheta, d, turn, arc), (vx2) */
	[HYLO_LAYOUT_PLANAR] = { HYLO_LAYOUT_PLANAR, "planar", HYLO_RELATIVE_PLANAR, HYLO_FEATURES_PLANAR, 3,
				 { 3, 0, 1, 2, 5, 6, 7, 4 }, { 0, 1, 7, 8 }, 1, 1 },
	/* (dp, v1, v2): (v1), (dp), (v2) */
	[HYLO_LAYOUT_SPATIAL] = { HYLO_LAYOUT_SPATIAL, "spatial", HYLO_FEATURES_FLIGHT, HYLO_FEATURES_FLIGHT, 3,
				  { 3, 4, 5, 0, 1, 2, 6, 7, 8 }, { 0, 3, 6, 9 }, 1, 0 },
	/* (p1, v1, p2, v2, log prior): (p1, v1), (p2, v2, log prior) */
	[HYLO_LAYOUT_PHASE] = { HYLO_LAYOUT_PHASE, "phase", HYLO_RELATIVE_DI, HYLO_FEATURES_DI, 2,
				{ 0, 1, 2, 3, 4 }, { 0, 2, 5 }, 0, 0 },
};

#define PLANAR_COORDS { { "px", "m" }, { "py", "m" }, { "vx", "m/s" }, { "theta", "rad" } }
/* the phase plane's units, as the map's (docs/models.md section 2) */
#define PHASE_COORDS { { "p", "m" }, { "v", "m/s" } }

/* One record per mode (docs/models.md). */
static const hylo_mode_desc modes[HYLO_MODE_COUNT] = {
	[HYLO_MODE_GROUND] = {
		.mode = HYLO_MODE_GROUND, .name = "ground", .c_name = "HYLO_MODE_GROUND",
		.xs_dim = 4, .coord = PLANAR_COORDS, .speed_index = 2, .speed_width = 1,
		.distance_dims = 2, .planar = 1, .air = 0, .domain = HYLO_DOMAIN_LAND,
		.layout = HYLO_LAYOUT_PLANAR, .nx = 6, .nu = 2,
	},
	[HYLO_MODE_MARINE] = {
		.mode = HYLO_MODE_MARINE, .name = "marine", .c_name = "HYLO_MODE_MARINE",
		.xs_dim = 4, .coord = PLANAR_COORDS, .speed_index = 2, .speed_width = 1,
		.distance_dims = 2, .planar = 1, .air = 0, .domain = HYLO_DOMAIN_WATER,
		.layout = HYLO_LAYOUT_PLANAR, .nx = 8, .nu = 2,
	},
	[HYLO_MODE_FLIGHT] = {
		.mode = HYLO_MODE_FLIGHT, .name = "flight", .c_name = "HYLO_MODE_FLIGHT",
		.xs_dim = 6,
		.coord = { { "px", "m" }, { "py", "m" }, { "pz", "m" },
			   { "vx", "m/s" }, { "vy", "m/s" }, { "vz", "m/s" } },
		.speed_index = 3, .speed_width = 3, .distance_dims = 3, .planar = 0, .air = 1,
		.domain = HYLO_DOMAIN_AIR, .layout = HYLO_LAYOUT_SPATIAL, .nx = 16, .nu = 4,
	},
	[HYLO_MODE_DI_NEG] = {
		.mode = HYLO_MODE_DI_NEG, .name = "di_neg", .c_name = "HYLO_MODE_DI_NEG",
		.xs_dim = 2, .coord = PHASE_COORDS, .speed_index = 1, .speed_width = 1,
		.distance_dims = 2, .planar = 0, .air = 0, .domain = HYLO_DOMAIN_PHASE, .side = -1,
		.layout = HYLO_LAYOUT_PHASE, .nx = 2, .nu = 1,
	},
	[HYLO_MODE_DI_POS] = {
		.mode = HYLO_MODE_DI_POS, .name = "di_pos", .c_name = "HYLO_MODE_DI_POS",
		.xs_dim = 2, .coord = PHASE_COORDS, .speed_index = 1, .speed_width = 1,
		.distance_dims = 2, .planar = 0, .air = 0, .domain = HYLO_DOMAIN_PHASE, .side = 1,
		.damped = 1, .layout = HYLO_LAYOUT_PHASE, .nx = 2, .nu = 1,
	},
#ifdef HYLO_EXTRA_MODE_RECORDS
	HYLO_EXTRA_MODE_RECORDS
#endif
};

const hylo_mode_desc *hylo_mode_describe(hylo_mode mode)
{
	return (int)mode > HYLO_MODE_NONE && (int)mode < HYLO_MODE_COUNT ? &modes[mode] : NULL;
}

hylo_mode hylo_mode_parse(const char *name)
{
	int m;

	for (m = HYLO_MODE_NONE + 1; name && m < HYLO_MODE_COUNT; m++)
		if (strcmp(modes[m].name, name) == 0)
			return (hylo_mode)m;
	return HYLO_MODE_NONE;
}

char *hylo_mode_names(char *out, size_t n)
{
	size_t used = 0;
	int m, w;

	if (!out || n == 0)
		return out;
	out[0] = '\0';
	for (m = HYLO_MODE_NONE + 1; m < HYLO_MODE_COUNT && used < n; m++) {
		w = snprintf(out + used, n - used, "%s%s", m > HYLO_MODE_NONE + 1 ? ", " : "", modes[m].name);
		if (w < 0)
			break;
		used += (size_t)w;
	}
	return out;
}

hylo_domain_kind hylo_mode_domain(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d ? d->domain : HYLO_DOMAIN_NONE;
}

const hylo_feature_layout *hylo_feature_layout_of(hylo_layout_kind kind)
{
	return (int)kind > HYLO_LAYOUT_NONE && (int)kind < HYLO_LAYOUT_COUNT ? &layouts[kind] : NULL;
}

const hylo_feature_layout *hylo_mode_layout(hylo_mode mode)
{
	const hylo_mode_desc *d = hylo_mode_describe(mode);

	return d ? hylo_feature_layout_of(d->layout) : NULL;
}

const hylo_feature_layout *hylo_feature_layout_of_count(uint32_t n_features)
{
	int k;

	for (k = HYLO_LAYOUT_NONE + 1; k < HYLO_LAYOUT_COUNT; k++)
		if (layouts[k].n_features == n_features)
			return &layouts[k];
	return NULL;
}
