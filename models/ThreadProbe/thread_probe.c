/* ThreadProbe.mo: `thread` is the Linux thread id of the thread that last computed the
 * outputs (each fmi2DoStep does), so a master's tests can see which of its threads stepped
 * the FMU. */
#define _GNU_SOURCE
#include <unistd.h>

#include "model.h"

enum { VR_THREAD, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    [VR_THREAD] = {"thread", VR_THREAD, TYPE_REAL, CAUSALITY_OUTPUT, VARIABILITY_DISCRETE,
                   INITIAL_CALCULATED, NULL, 0, "id of the thread that last stepped the FMU", -1,
                   DEPENDS_NONE, DEPENDS_NONE},
};

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    (void)x;
    v[VR_THREAD] = (double)gettid();
}

const model_definition fmu_model = {
    .name = "ThreadProbe",
    .description = "Reports the thread that stepped it (ThreadProbe.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
};
