/*
 * Every committed ground, marine and flight model (onboard/models/, through
 * the node's registry) carries an envelope, and the envelope is a lower
 * bound of the model's own prediction: for 20,000 seeded random edges per
 * model (random positions and headings, distances up to max_distance_m,
 * flight random climbs within that ball and level velocities of any
 * direction, speeds on the table's nodes) hylo_svr_predict >=
 * hylo_envelope_of_edge, and the bound is not 0 (no edge of the training
 * range falls outside the table). Negative control: the same table with
 * every value 5% higher must be caught, so that the check would fail on an
 * envelope that is not a bound. The flight model's turn table (by distance
 * and turn instead of climb) is part of hylo_envelope_of_edge: it must
 * raise some of the bounds, and a turn table 5% higher must be caught too. Ground and marine tables have 16 turn cells
 * over [0, 2 pi], and also bound the edges that stay in place (turn 0 by
 * definition, whose features depend on the tail heading's quadrant), which
 * random edges never hit. The trainer measures the random edges on 10^6
 * per model before it exports a table (trainer/envelope.cpp).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hylo/envelope.h"
#include "hylo/features.h"
#include "node/registry.h"
#include "tools/cost/random_edge.h"

#define EDGES 20000
#define MAX_VALUES 300000

static float scaled[MAX_VALUES], scaled_turn[MAX_VALUES];

/* *out: table e with every value 5% higher, held in buf. */
static void five_percent_higher(const hylo_svr_envelope *e, float *buf, hylo_svr_envelope *out)
{
	uint32_t n_values = e->n_d * e->n_z * e->n_v * e->n_v, i;

	assert_true(n_values <= MAX_VALUES);
	for (i = 0; i < n_values; i++)
		buf[i] = e->value[i] * 1.05f;
	*out = *e;
	out->value = buf;
}

/* Ground, marine: the turn axis, and edges in place for 12 x 12 tail and
 * head headings and every speed pair. */
static void check_turns_and_in_place(const hylo_svr_model *m, hylo_mode mode)
{
	const hylo_svr_envelope *e = m->envelope;
	uint32_t i, l, a, b, below = 0, zero = 0;

	if (e->n_z != 16 || e->z_min != 0 || e->z_step != 2 * PI / 16)
		fail_msg("%s: %u turn cells of %g rad from %g, not 16 over [0, 2 pi]", m->name, e->n_z,
			 e->z_step, e->z_min);
	for (i = 0; i < 12; i++)
		for (l = 0; l < 12; l++)
			for (a = 0; a < e->n_v; a++)
				for (b = 0; b < e->n_v; b++) {
					double t[4], h[4], f[HYLO_FEATURES_PLANAR], cost, bound;

					t[0] = h[0] = 7.5, t[1] = h[1] = -3.25;
					t[2] = e->v_min + a * e->v_step, h[2] = e->v_min + b * e->v_step;
					t[3] = -PI + (i + 0.5) * 2 * PI / 12, h[3] = t[3] + l * 2 * PI / 12;
					hylo_features(mode, t, h, f);
					cost = hylo_svr_predict(m, f);
					bound = hylo_envelope_of_edge(m, mode, t, h);
					below += cost < bound;
					zero += bound == 0;
				}
	printf("# %s: %u of %u edges in place below the envelope, %u with no bound\n", m->name, below,
	       144 * e->n_v * e->n_v, zero);
	if (below > 0 || zero > 0)
		fail_msg("%s: %u edges in place cost less than the envelope, %u have none", m->name, below, zero);
}

static void check_model(const hylo_registry_model *r)
{
	const hylo_svr_model *m = r->model;
	const hylo_svr_envelope *e = m->envelope, *t = m->turn_envelope;
	hylo_svr_envelope high, turn_high;
	hylo_svr_model m_high, m_turn_high, m_climb;
	uint32_t i, below = 0, zero = 0, caught = 0, caught_turn = 0, raised = 0;
	double closest = INFINITY, worst = 0;

	if (!e)
		fail_msg("%s has no envelope", m->name);
	assert_int_equal(hylo_svr_check(m, NULL), HYLO_OK);
	five_percent_higher(e, scaled, &high);
	m_high = *m;
	m_high.envelope = &high;
	/* Flight: the turn table alone 5% higher, and the climb table alone. */
	m_turn_high = *m;
	m_climb = *m;
	m_climb.turn_envelope = NULL;
	if (t) {
		five_percent_higher(t, scaled_turn, &turn_high);
		m_turn_high.turn_envelope = &turn_high;
	}
	rng_state = 20260101u + (uint64_t)r->mode;
	for (i = 0; i < EDGES; i++) {
		double tail[HYLO_XS_DIM], head[HYLO_XS_DIM], f[HYLO_MAX_FEATURES], cost, bound;

		random_edge(m, r->mode, EDGE_RANDOM, tail, head);
		hylo_features(r->mode, tail, head, f);
		cost = hylo_svr_predict(m, f);
		bound = hylo_envelope_of_edge(m, r->mode, tail, head);
		zero += bound == 0;
		if (cost < bound) {
			below++;
			worst = fmax(worst, (bound - cost) / cost);
		}
		closest = fmin(closest, (cost - bound) / cost);
		caught += cost < hylo_envelope_of_edge(&m_high, r->mode, tail, head);
		if (t) {
			caught_turn += cost < hylo_envelope_of_edge(&m_turn_high, r->mode, tail, head);
			raised += bound > hylo_envelope_of_edge(&m_climb, r->mode, tail, head);
		}
	}
	printf("# %s: %u of %d edges below the envelope (worst %.3g), closest %.3g relative above it; "
	       "%u with no bound; a table 5%% higher: %u below\n",
	       m->name, below, EDGES, worst, closest, zero, caught);
	if (below > 0)
		fail_msg("%s: %u of %d random edges cost less than the envelope (by up to %.3g relative)",
			 m->name, below, EDGES, worst);
	if (zero > 0)
		fail_msg("%s: %u of %d edges within the training range have no bound", m->name, zero, EDGES);
	if (caught == 0)
		fail_msg("%s: the check does not notice a table 5%% too high", m->name);
	if (t) {
		printf("# %s: the turn table raises %u of %d bounds; a turn table 5%% higher: %u below\n",
		       m->name, raised, EDGES, caught_turn);
		if (raised == 0 || caught_turn == 0)
			fail_msg("%s: the turn table raises %u bounds, one 5%% higher is caught %u times",
				 m->name, raised, caught_turn);
	}
	if (r->mode == HYLO_MODE_GROUND || r->mode == HYLO_MODE_MARINE)
		check_turns_and_in_place(m, r->mode);
}

/* One model, named by the test's state. */
static void test_model(void **state)
{
	const char *name = (const char *)*state;
	uint32_t k;

	for (k = 0; k < hylo_registry_n_models; k++)
		if (strcmp(hylo_registry_models[k].model->name, name) == 0) {
			check_model(&hylo_registry_models[k]);
			return;
		}
	fail_msg("no committed model %s", name);
}

/* Ground, marine and flight models have an envelope, flight ones a turn
 * table too; the double integrator's none (its features are absolute
 * positions). */
static void test_which_models(void **state)
{
	uint32_t k;

	(void)state;
	for (k = 0; k < hylo_registry_n_models; k++) {
		const hylo_registry_model *r = &hylo_registry_models[k];
		int di = r->mode == HYLO_MODE_DI_NEG || r->mode == HYLO_MODE_DI_POS;

		if (di != (r->model->envelope == NULL))
			fail_msg("%s: %s", r->model->name, di ? "an envelope" : "no envelope");
		if ((r->mode == HYLO_MODE_FLIGHT) != (r->model->turn_envelope != NULL))
			fail_msg("%s: %s", r->model->name,
				 r->mode == HYLO_MODE_FLIGHT ? "no turn table" : "a turn table");
		assert_null(r->feasibility ? r->feasibility->envelope : NULL);
		assert_null(r->feasibility ? r->feasibility->turn_envelope : NULL);
	}
}

int main(void)
{
	static const char *names[] = { "ambot_ground", "ambot_marine", "drivocopter_ground",
				       "drivocopter_flight" };
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_which_models),
		{ "ambot_ground: 20,000 random edges cost at least the envelope", test_model, NULL, NULL,
		  (void *)names[0] },
		{ "ambot_marine: 20,000 random edges cost at least the envelope", test_model, NULL, NULL,
		  (void *)names[1] },
		{ "drivocopter_ground: 20,000 random edges cost at least the envelope", test_model, NULL,
		  NULL, (void *)names[2] },
		{ "drivocopter_flight: 20,000 random edges cost at least the envelope", test_model, NULL,
		  NULL, (void *)names[3] },
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
