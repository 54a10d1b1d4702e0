/* Sum.mo: y = b - c * u (with a gain, the smallest algebraic loop: y = b - c k y).
 * The input is in centimetres and the output in metres, so that a loop through the gain (metres)
 * converts units inside the loop; c carries the factor from cm to m (c = 0.01 is a unit weight). */
#include "model.h"

enum { VR_Y, VR_U, VR_B, VR_C, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_Y, "y", "m", "output b - c * u", DEPENDS(VR_U), DEPENDS(VR_U, VR_B, VR_C)),
    REAL_INPUT(VR_U, "u", "cm", 0, "input"),
    REAL_PARAMETER(VR_B, "b", "m", 0, "offset"),
    REAL_PARAMETER(VR_C, "c", NULL, 1, "weight of the input, in m per cm of input"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    (void)x;
    v[VR_Y] = v[VR_B] - v[VR_C] * v[VR_U];
}

static double partial_derivative(const double *v, const double *x, unsigned output,
                                 unsigned input)
{
    (void)x;
    return output == VR_Y && input == VR_U ? -v[VR_C] : 0.0;
}

const model_definition fmu_model = {
    .name = "Sum",
    .description = "Offset minus weighted input (Sum.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
    .partial_derivative = partial_derivative,
};
