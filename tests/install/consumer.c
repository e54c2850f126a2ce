/*
 * A C99 program built out of the tree against an installed hylo with
 * pkg-config (tests/install/test_install.sh):
 *   cc -std=c99 consumer.c $(pkg-config --cflags --libs hylo)
 * It plans the double integrator's scene with the committed models
 * (consumer.h) and exits 0 when the plan is right.
 */
#include "consumer.h"

int main(void)
{
	return consumer_plan();
}
