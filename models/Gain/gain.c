/* Gain.mo: y = k * u, a length in metres to a length in metres. */
#include "model.h"

enum { VR_Y, VR_U, VR_K, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_Y, "y", "m", "output k * u", DEPENDS(VR_U), DEPENDS(VR_U, VR_K)),
    REAL_INPUT(VR_U, "u", "m", 0, "input"),
    REAL_PARAMETER(VR_K, "k", NULL, 1, "gain"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    (void)x;
    v[VR_Y] = v[VR_K] * v[VR_U];
}

static double partial_derivative(const double *v, const double *x, unsigned output,
                                 unsigned input)
{
    (void)x;
    return output == VR_Y && input == VR_U ? v[VR_K] : 0.0;
}

const model_definition fmu_model = {
    .name = "Gain",
    .description = "Static gain (Gain.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
    .partial_derivative = partial_derivative,
};
