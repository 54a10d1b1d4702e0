/* Terminating.mo: a ramp y = y0 + slope * t that asks the master to end the simulation at
 * stop_time. fmi2DoStep integrates up to stop_time, returns fmi2Discard, and fmi2GetBooleanStatus
 * (fmi2Terminated) answers true, as the Reference FMU Stair does at t = 9. */
#include "model.h"

enum { VR_Y, VR_Y0, VR_SLOPE, VR_STOP_TIME, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_Y, "y", NULL, "the ramp y0 + slope * t", DEPENDS_NONE, DEPENDS(VR_Y0, VR_SLOPE)),
    REAL_PARAMETER(VR_Y0, "y0", NULL, 0, "value at t = 0"),
    REAL_PARAMETER(VR_SLOPE, "slope", NULL, 1, "slope of the ramp (1/s)"),
    REAL_PARAMETER(VR_STOP_TIME, "stop_time", "s", 1, "the model asks to stop at this time"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)x;
    v[VR_Y] = v[VR_Y0] + v[VR_SLOPE] * t;
}

static double termination_time(const double *v)
{
    return v[VR_STOP_TIME];
}

const model_definition fmu_model = {
    .name = "Terminating",
    .description = "A ramp that asks to stop at stop_time (Terminating.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 2.0,
    .default_step_size = 0.1,
    .outputs = outputs,
    .termination_time = termination_time,
};
