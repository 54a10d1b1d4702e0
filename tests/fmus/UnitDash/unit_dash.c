/* UnitDash.mo: y = k * u, every variable with the unit "-", which Parker and Hopsan exports
 * use for "dimensionless" and which pint cannot parse. */
#include "model.h"

enum { VR_Y, VR_U, VR_K, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    [VR_Y] = {"y", VR_Y, TYPE_REAL, CAUSALITY_OUTPUT, VARIABILITY_CONTINUOUS, INITIAL_CALCULATED,
              "-", 0, "output k * u", -1, DEPENDS(VR_U), DEPENDS(VR_U, VR_K)},
    [VR_U] = {"u", VR_U, TYPE_REAL, CAUSALITY_INPUT, VARIABILITY_CONTINUOUS, INITIAL_NONE, "-", 0,
              "input", -1, NULL, NULL},
    REAL_PARAMETER(VR_K, "k", "-", 2, "gain"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    (void)x;
    v[VR_Y] = v[VR_K] * v[VR_U];
}

const model_definition fmu_model = {
    .name = "UnitDash",
    .description = "Static gain with the unit \"-\" (UnitDash.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
};
