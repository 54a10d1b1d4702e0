/* UnitDash.mo: y = k * u, every variable with the unit "-", which Parker and Hopsan exports
 * use for "dimensionless" and which pint cannot parse. */
#include "model.h"

enum { VR_Y, VR_U, VR_K, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_Y, "y", "-", "output k * u", DEPENDS(VR_U), DEPENDS(VR_U, VR_K)),
    REAL_INPUT(VR_U, "u", "-", 0, "input"),
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
