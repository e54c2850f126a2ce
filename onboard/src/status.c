#include "hylo/status.h"

#include <stdarg.h>
#include <stdio.h>

static const char *const status_names[HYLO_STATUS_COUNT] = {
	[HYLO_OK] = "ok",
	[HYLO_E_NULL] = "null argument",
	[HYLO_E_BAD_VALUE] = "bad value",
	[HYLO_E_BAD_MAP] = "bad map",
	[HYLO_E_NO_MAP] = "no map",
	[HYLO_E_UNKNOWN_ROBOT] = "unknown robot",
	[HYLO_E_NO_MODEL] = "no cost model",
	[HYLO_E_WRONG_MODE] = "wrong mode",
	[HYLO_E_OUTSIDE_DOMAIN] = "outside domain",
	[HYLO_E_EMPTY_DOMAIN] = "empty domain",
	[HYLO_E_BAD_COST] = "bad cost",
	[HYLO_E_MAP_MISMATCH] = "map mismatch",
	[HYLO_E_CAP_CELLS] = "capacity exceeded: cells",
	[HYLO_E_CAP_POSITIONS] = "capacity exceeded: positions",
	[HYLO_E_CAP_NODES] = "capacity exceeded: nodes",
	[HYLO_E_CAP_ADJACENCY] = "capacity exceeded: adjacency",
	[HYLO_E_CAP_GRID] = "capacity exceeded: grid",
	[HYLO_E_CAP_COMBOS] = "capacity exceeded: combos",
	[HYLO_E_CAP_SUCCESSORS] = "capacity exceeded: successors",
	[HYLO_E_CAP_WAYPOINTS] = "capacity exceeded: waypoints",
	[HYLO_E_CAP_BUCKETS] = "capacity exceeded: buckets",
	[HYLO_E_CAP_SV] = "capacity exceeded: support vectors",
	[HYLO_E_CAP_ROBOTS] = "capacity exceeded: robots",
};

static const char *const outcome_names[HYLO_OUTCOME_COUNT] = {
	[HYLO_FOUND] = "found",
	[HYLO_NO_PATH] = "no path",
	[HYLO_BUDGET_EXHAUSTED] = "budget exhausted",
	[HYLO_FOUND_UNPROVEN] = "found, not proven optimal (the budget ran out)",
};

const char *hylo_status_str(hylo_status s)
{
	if ((unsigned)s >= HYLO_STATUS_COUNT || !status_names[s])
		return "unknown status";
	return status_names[s];
}

const char *hylo_outcome_str(hylo_outcome o)
{
	if ((unsigned)o >= HYLO_OUTCOME_COUNT || !outcome_names[o])
		return "unknown outcome";
	return outcome_names[o];
}

hylo_status hylo_fail(hylo_reason *r, hylo_status s, const char *fmt, ...)
{
	va_list ap;

	if (!r)
		return s;
	va_start(ap, fmt);
	vsnprintf(r->text, sizeof r->text, fmt, ap);
	va_end(ap);
	return s;
}

void hylo_reason_clear(hylo_reason *r)
{
	if (r)
		snprintf(r->text, sizeof r->text, "ok");
}
