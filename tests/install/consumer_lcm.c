/*
 * A C99 program built out of the tree against an installed hylo's LCM
 * package (tests/install/test_install.sh):
 *   cc -std=c99 consumer_lcm.c $(pkg-config --cflags --libs hylo-lcm)
 * It turns a plan into a plan_t with the installed adaptors (hylo_msg.h),
 * publishes it over LCM's in-process memq:// provider with the installed C
 * bindings and checks what its own subscription receives.
 */
#include <stdio.h>
#include <string.h>

#include <hylo_msg.h>
#include <hylo_plan_t.h>
#include <lcm/lcm.h>

static int received;
static double received_cost;
static int32_t received_waypoints;

static void on_plan(const lcm_recv_buf_t *rbuf, const char *channel, const hylo_plan_t *msg, void *user)
{
	(void)rbuf;
	(void)channel;
	(void)user;
	received++;
	received_cost = msg->total_cost_j;
	received_waypoints = msg->n_waypoints;
}

int main(void)
{
	static hylo_plan plan;
	hylo_plan_msg_buf buf;
	hylo_plan_t msg;
	lcm_t *lcm;
	int rc = 0;

	memset(&plan, 0, sizeof plan);
	plan.status = HYLO_OK;
	plan.outcome = HYLO_FOUND;
	plan.request_id = 7;
	strcpy(plan.robot, "di");
	plan.total_cost = 1.25;
	plan.suboptimality = 1;
	plan.n_waypoints = 2;
	plan.mode[0] = plan.mode[1] = HYLO_MODE_DI_POS;
	plan.state[1][0] = 0.5;
	plan.cost[1] = 1.25;
	plan.n_modes = 1;
	plan.mode_sequence[0] = HYLO_MODE_DI_POS;
	hylo_msg_plan(&plan, 1, &buf, &msg);

	lcm = lcm_create("memq://");
	if (!lcm) {
		fprintf(stderr, "consumer_lcm: lcm_create(memq://) failed\n");
		return 1;
	}
	hylo_plan_t_subscribe(lcm, "HYLO_PLAN", on_plan, NULL);
	if (hylo_plan_t_publish(lcm, "HYLO_PLAN", &msg) != 0 || lcm_handle_timeout(lcm, 1000) <= 0) {
		fprintf(stderr, "consumer_lcm: publishing or handling failed\n");
		rc = 1;
	} else if (received != 1 || received_cost != 1.25 || received_waypoints != 2 ||
		   msg.status != hylo_msg_plan_status(HYLO_OK, HYLO_FOUND)) {
		fprintf(stderr, "consumer_lcm: received %d plans, cost %g, %d waypoints\n", received,
			received_cost, (int)received_waypoints);
		rc = 1;
	} else {
		printf("plan_t over memq://: %d waypoints, cost %g\n", (int)received_waypoints, received_cost);
	}
	lcm_destroy(lcm);
	return rc;
}
