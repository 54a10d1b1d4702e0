/* Jacobi and Gauss-Seidel on a counter feeding a sampler (hooks, as Python components): under
 * Gauss-Seidel the sampler sees the counter's newest value, under Jacobi the previous one. */
#include <math.h>

#include "hook_components.h"
#include "test_support.h"

/* Ten steps of 0.1; the sampler must lag the counter by expected_lag steps. */
static void run(ssx_coupling coupling, int sampler_first, double scale, double offset,
                double expected_lag)
{
    ssx_system *sys = ssx_system_new("coupling");
    hook_component counter, sampler;
    int c = hook_add(sys, "counter", &counter, hook_count, 0);
    int s = hook_add(sys, "sampler", &sampler, hook_sample, 1);
    CHECK_OK(sys, ssx_connect(sys, c, 0, s, 0, scale, offset));
    CHECK_OK(sys, ssx_set_coupling(sys, coupling));
    if (sampler_first) {
        const int order[] = {s, c};
        const int sizes[] = {1, 1};
        CHECK_OK(sys, ssx_set_schedule(sys, order, sizes, NULL, 2));
    }
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.1));
    const double *counted = ssx_history_values(sys, c);
    const double *sampled = ssx_history_values(sys, s);
    CHECK(ssx_history_length(sys) == 11);
    for (size_t k = 1; k < 11; ++k) {
        CHECK(counted[k] == (double)k);
        CHECK(sampled[k] == scale * ((double)k - expected_lag) + offset);
    }
    ssx_system_free(sys);
}

int main(void)
{
    run(SSX_GAUSS_SEIDEL, 0, 1.0, 0.0, 0.0);
    run(SSX_GAUSS_SEIDEL, 1, 1.0, 0.0, 1.0); /* the sampler steps before the counter */
    run(SSX_JACOBI, 0, 1.0, 0.0, 1.0);
    run(SSX_JACOBI, 1, 1.0, 0.0, 1.0);
    run(SSX_GAUSS_SEIDEL, 0, 2.0, 0.5, 0.0); /* scale and offset applied on the way */
    return 0;
}
