/* Failing.mo: y = u, and fmi2DoStep returns fmi2Error (with a log message) for any step that
 * ends after fail_time. It lets masters test how they report a failing FMU. */
#include "model.h"

enum { VR_Y, VR_U, VR_FAIL_TIME, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    [VR_Y] = {"y", VR_Y, TYPE_REAL, CAUSALITY_OUTPUT, VARIABILITY_CONTINUOUS, INITIAL_CALCULATED,
              NULL, 0, "copy of the input", -1, DEPENDS(VR_U), DEPENDS(VR_U)},
    [VR_U] = {"u", VR_U, TYPE_REAL, CAUSALITY_INPUT, VARIABILITY_CONTINUOUS, INITIAL_NONE, NULL, 0,
              "input", -1, NULL, NULL},
    REAL_PARAMETER(VR_FAIL_TIME, "fail_time", "s", 1, "steps ending after this time fail"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    (void)x;
    v[VR_Y] = v[VR_U];
}

static const char *step_refusal(const double *v, double t_end)
{
    return t_end > v[VR_FAIL_TIME] ? "the simulation passed fail_time (a deliberate failure)"
                                   : NULL;
}

const model_definition fmu_model = {
    .name = "Failing",
    .description = "Copies its input and fails after fail_time (Failing.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
    .step_refusal = step_refusal,
};
