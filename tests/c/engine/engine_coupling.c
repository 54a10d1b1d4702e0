/* Jacobi and Gauss-Seidel on a counter feeding a sampler (hooks, as Python components): under
 * Gauss-Seidel the sampler sees the counter's newest value, under Jacobi the previous one. */
#include <math.h>

#include "test_support.h"

typedef struct {
    ssx_system *sys;
    int component;
} block;

/* counter: its output counts the steps taken */
static int count(void *user, double t, double dt)
{
    (void)t;
    (void)dt;
    block *b = user;
    ssx_outputs(b->sys, b->component)[0] += 1.0;
    return 0;
}

/* sampler: holds the input it saw when it stepped */
static int sample(void *user, double t, double dt)
{
    (void)t;
    (void)dt;
    block *b = user;
    ssx_outputs(b->sys, b->component)[0] = ssx_inputs(b->sys, b->component)[0];
    return 0;
}

static int keep(void *user, double t)
{
    (void)user;
    (void)t;
    return 0;
}

static int add(ssx_system *sys, const char *name, block *b, int (*do_step)(void *, double, double),
               int with_input)
{
    int c = ssx_add_python_component(sys, name, 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, 0) == 0);
    if (with_input) {
        CHECK(ssx_add_input(sys, c, SSX_REAL, 0, 0.0) == 0);
    }
    *b = (block){.sys = sys, .component = c};
    ssx_hooks hooks = {.user = b, .do_step = do_step, .evaluate_outputs = keep};
    CHECK_OK(sys, ssx_set_hooks(sys, c, &hooks));
    return c;
}

/* Ten steps of 0.1; the sampler must lag the counter by expected_lag steps. */
static void run(ssx_coupling coupling, int sampler_first, double scale, double offset,
                double expected_lag)
{
    ssx_system *sys = ssx_system_new("coupling");
    block counter, sampler;
    int c = add(sys, "counter", &counter, count, 0);
    int s = add(sys, "sampler", &sampler, sample, 1);
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
