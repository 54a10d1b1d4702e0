/* The port values of every component lie in one block in schedule order (port_block.h): laid
 * out by ssx_initialize, kept by the next one while the structure stands, and given back to a
 * component that gets a new port, with every value where it was. Three hook components added
 * in the reverse of their schedule: a counter, a doubler of the count, a sampler of the
 * doubled count. */
#include "hook_components.h"
#include "test_support.h"

/* doubler: its output is twice its input */
static int twice(void *user, double t, double dt)
{
    (void)t;
    (void)dt;
    hook_component *b = user;
    ssx_outputs(b->sys, b->component)[0] = 2.0 * ssx_inputs(b->sys, b->component)[0];
    return 0;
}

/* After `steps` steps of 0.1 from the last run's end: the count, doubled, sampled. */
static void check_values(ssx_system *sys, int counter, int doubler, int sampler, double steps)
{
    CHECK(ssx_outputs(sys, counter)[0] == steps);
    CHECK(ssx_inputs(sys, doubler)[0] == steps);
    CHECK(ssx_outputs(sys, doubler)[0] == 2.0 * steps);
    CHECK(ssx_inputs(sys, sampler)[0] == 2.0 * steps);
    CHECK(ssx_outputs(sys, sampler)[0] == 2.0 * steps);
}

int main(void)
{
    ssx_system *sys = ssx_system_new("port block");
    hook_component sampler_block, doubler_block, counter_block;
    int sampler = hook_add(sys, "sampler", &sampler_block, hook_sample, 1);
    int doubler = hook_add(sys, "doubler", &doubler_block, twice, 1);
    int counter = hook_add(sys, "counter", &counter_block, hook_count, 0);
    CHECK_OK(sys, ssx_connect(sys, counter, 0, doubler, 0, 1.0, 0.0));
    CHECK_OK(sys, ssx_connect(sys, doubler, 0, sampler, 0, 1.0, 0.0));
    const int order[] = {counter, doubler, sampler};
    const int sizes[] = {1, 1, 1};
    CHECK_OK(sys, ssx_set_schedule(sys, order, sizes, NULL, 3));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));

    /* each member's inputs, then its outputs, member after member in schedule order */
    double *first = ssx_outputs(sys, counter);
    CHECK(ssx_inputs(sys, doubler) == first + 1);
    CHECK(ssx_outputs(sys, doubler) == first + 2);
    CHECK(ssx_inputs(sys, sampler) == first + 3);
    CHECK(ssx_outputs(sys, sampler) == first + 4);

    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.1));
    check_values(sys, counter, doubler, sampler, 10.0);
    const double *sampled = ssx_history_values(sys, sampler);
    for (size_t k = 1; k < ssx_history_length(sys); ++k) {
        CHECK(sampled[k] == 2.0 * (double)k); /* Gauss-Seidel: no lag along the schedule */
    }

    /* initialized again with the same structure: the values stay where they are */
    CHECK_OK(sys, ssx_initialize(sys, 1.0));
    CHECK(ssx_outputs(sys, counter) == first);
    CHECK(ssx_outputs(sys, sampler) == first + 4);

    /* a new port gives the doubler arrays of its own, with its values */
    CHECK(ssx_add_output(sys, doubler, SSX_REAL, 1) == 1);
    CHECK(ssx_outputs(sys, doubler)[0] == 20.0);
    CHECK(ssx_outputs(sys, doubler)[1] == 0.0);
    CHECK(ssx_inputs(sys, doubler)[0] == 10.0);
    check_values(sys, counter, doubler, sampler, 10.0);

    /* and the next initialize lays the block out again, the doubler's two outputs in it */
    CHECK_OK(sys, ssx_initialize(sys, 1.0));
    first = ssx_outputs(sys, counter);
    CHECK(ssx_inputs(sys, doubler) == first + 1);
    CHECK(ssx_outputs(sys, doubler) == first + 2);
    CHECK(ssx_inputs(sys, sampler) == first + 4);
    CHECK_OK(sys, ssx_run(sys, 1.0, 2.0, 0.1));
    check_values(sys, counter, doubler, sampler, 20.0);
    ssx_system_free(sys);
    return 0;
}
