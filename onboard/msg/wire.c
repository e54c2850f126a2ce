/*
 * Checks of encoded LCM messages before they are decoded. lcm-gen's decoders
 * allocate each variable-length array with the count read from the wire
 * before checking that the buffer holds it, and accept negative counts; a
 * corrupt message could ask for gigabytes or yield negative sizes. These
 * walkers follow the wire layout of the msgs/ types (big-endian scalars; a string
 * is an int32 length that counts its NUL, then the bytes) and accept only
 * messages whose fingerprint matches, whose counts (and max_expansions) are
 * non-negative and whose length is exact. They allocate nothing. Keep in step with msgs/.
 */
#include <stdint.h>
#include <string.h>

#include "hylo_msg.h"

typedef struct {
	const uint8_t *p;
	int len, pos;
	const char *what;     /* message type, for reasons */
	hylo_reason *r;
	hylo_status st;       /* first failure */
} wire;

static int64_t be64(const uint8_t *p)
{
	uint64_t v = 0;
	int i;

	for (i = 0; i < 8; i++)
		v = (v << 8) | p[i];
	return (int64_t)v;
}

static int32_t be32(const uint8_t *p)
{
	return (int32_t)(((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) |
			 ((uint32_t)p[2] << 8) | (uint32_t)p[3]);
}

static int need(wire *w, long n, const char *field)
{
	if (w->st != HYLO_OK)
		return 0;
	if (n < 0 || n > (long)(w->len - w->pos)) {
		w->st = hylo_fail(w->r, HYLO_E_BAD_VALUE,
				  "%s message truncated at field %s (byte %d of %d)", w->what, field,
				  w->pos, w->len);
		return 0;
	}
	return 1;
}

static void skip(wire *w, long n, const char *field)
{
	if (need(w, n, field))
		w->pos += (int)n;
}

static int64_t get64(wire *w, const char *field)
{
	int64_t v = 0;

	if (need(w, 8, field)) {
		v = be64(w->p + w->pos);
		w->pos += 8;
	}
	return v;
}

static int32_t get_count(wire *w, const char *field)
{
	int32_t v = 0;

	if (!need(w, 4, field))
		return 0;
	v = be32(w->p + w->pos);
	w->pos += 4;
	if (v < 0) {
		w->st = hylo_fail(w->r, HYLO_E_BAD_VALUE, "%s message: %s is %ld, negative",
				  w->what, field, (long)v);
		return 0;
	}
	return v;
}

static void string_field(wire *w, const char *field)
{
	int32_t n = get_count(w, field);

	if (w->st == HYLO_OK && n == 0)
		w->st = hylo_fail(w->r, HYLO_E_BAD_VALUE, "%s message: string %s has length 0",
				  w->what, field);
	if (need(w, n, field) && w->p[w->pos + n - 1] != '\0')
		w->st = hylo_fail(w->r, HYLO_E_BAD_VALUE,
				  "%s message: string %s is not terminated", w->what, field);
	skip(w, n, field);
}

static void start(wire *w, const void *buf, int len, const char *what, int64_t hash,
		  hylo_reason *r)
{
	w->p = buf;
	w->len = buf && len > 0 ? len : 0;
	w->pos = 0;
	w->what = what;
	w->r = r;
	w->st = HYLO_OK;
	if (get64(w, "fingerprint") != hash && w->st == HYLO_OK)
		w->st = hylo_fail(r, HYLO_E_BAD_VALUE,
				  "%s message has a wrong type fingerprint (another type or "
				  "another version of msgs/)", what);
}

/*
 * Starts a message whose fingerprint and utime come before an int64 id:
 * *id (when id is not NULL) is that id if it can be read, else unreadable.
 */
static void start_with_id(wire *w, const void *buf, int len, const char *what, int64_t hash,
			  hylo_reason *r, int64_t *id, int64_t unreadable)
{
	if (id)
		*id = unreadable;
	start(w, buf, len, what, hash, r);
	skip(w, 8, "utime");
	if (w->st == HYLO_OK && w->len - w->pos >= 8 && id)
		*id = be64(w->p + w->pos);
}

/* An array: its int32 count, then that many elements of size bytes. */
static int32_t array_field(wire *w, long size, const char *count, const char *field)
{
	int32_t n = get_count(w, count);

	skip(w, size * n, field);
	return n;
}

static hylo_status finish(wire *w)
{
	if (w->st == HYLO_OK && w->pos != w->len)
		w->st = hylo_fail(w->r, HYLO_E_BAD_VALUE,
				  "%s message has %d bytes after its last field", w->what,
				  w->len - w->pos);
	if (w->st == HYLO_OK)
		hylo_reason_clear(w->r);
	return w->st;
}

hylo_status hylo_msg_check_goal(const void *buf, int len, int64_t *request_id,
				hylo_reason *r)
{
	wire w;

	start_with_id(&w, buf, len, "goal_t", __hylo_goal_t_get_hash(), r, request_id,
		      HYLO_GOAL_T_REQUEST_ID_UNREADABLE);
	skip(&w, 8 + 8 + 8 + 1 + 1 + 6 * 8 + 1 + 6 * 8 + 8, "request_id .. seed");
	skip(&w, 5 * 8, "spacing_m .. air_connect_radius_m");
	array_field(&w, 8, "n_speeds", "speeds_mps");
	array_field(&w, 8, "n_headings", "headings_rad");
	array_field(&w, 8, "n_air_speeds", "air_speeds_mps");
	skip(&w, 8, "time_budget_ms");
	get_count(&w, "max_expansions");
	skip(&w, 8, "suboptimality");
	if (need(&w, 1, "alternatives") && (int8_t)w.p[w.pos] < 0)
		w.st = hylo_fail(r, HYLO_E_BAD_VALUE, "goal_t message: alternatives is %d, negative",
				 (int)(int8_t)w.p[w.pos]);
	skip(&w, 1, "alternatives");
	skip(&w, 8, "alternatives_within");
	return finish(&w);
}

hylo_status hylo_msg_check_map(const void *buf, int len, int64_t *map_id, hylo_reason *r)
{
	wire w;
	int32_t n;

	start_with_id(&w, buf, len, "map_t", __hylo_map_t_get_hash(), r, map_id, 0);
	skip(&w, 8, "map_id");
	string_field(&w, "robot");
	skip(&w, 4 + 4 + 5 * 8, "nx .. max_step_m");
	n = array_field(&w, 1, "n_cells", "terrain");
	skip(&w, 4L * n, "height_m");
	return finish(&w);
}
