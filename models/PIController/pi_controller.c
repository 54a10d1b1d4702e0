/* PIController.mo: u = kp e + ki * integral(e), e = setpoint - measurement. Built with the
 * Euler back-end, which integrates the piecewise-constant error of a co-simulation exactly. */
#include "model.h"

enum {
    VR_U, VR_INTEGRAL, VR_DER_INTEGRAL, VR_SETPOINT, VR_MEASUREMENT, VR_KP, VR_KI, VR_INTEGRAL0,
    VARIABLE_COUNT
};

static const model_variable variables[VARIABLE_COUNT] = {
    [VR_U] = {"u", VR_U, TYPE_REAL, CAUSALITY_OUTPUT, VARIABILITY_CONTINUOUS, INITIAL_CALCULATED,
              NULL, 0, "controller output", -1,
              DEPENDS(VR_INTEGRAL, VR_SETPOINT, VR_MEASUREMENT),
              DEPENDS(VR_SETPOINT, VR_MEASUREMENT, VR_KP, VR_KI, VR_INTEGRAL0)},
    [VR_INTEGRAL] = {"integral", VR_INTEGRAL, TYPE_REAL, CAUSALITY_LOCAL, VARIABILITY_CONTINUOUS,
                     INITIAL_CALCULATED, NULL, 0, "integral of the error", -1, NULL,
                     DEPENDS(VR_INTEGRAL0)},
    [VR_DER_INTEGRAL] = {"der(integral)", VR_DER_INTEGRAL, TYPE_REAL, CAUSALITY_LOCAL,
                         VARIABILITY_CONTINUOUS, INITIAL_CALCULATED, NULL, 0,
                         "the error setpoint - measurement", VR_INTEGRAL,
                         DEPENDS(VR_SETPOINT, VR_MEASUREMENT),
                         DEPENDS(VR_SETPOINT, VR_MEASUREMENT)},
    [VR_SETPOINT] = {"setpoint", VR_SETPOINT, TYPE_REAL, CAUSALITY_INPUT, VARIABILITY_CONTINUOUS,
                     INITIAL_NONE, NULL, 0, "reference value", -1, NULL, NULL},
    [VR_MEASUREMENT] = {"measurement", VR_MEASUREMENT, TYPE_REAL, CAUSALITY_INPUT,
                        VARIABILITY_CONTINUOUS, INITIAL_NONE, NULL, 0, "measured value", -1,
                        NULL, NULL},
    REAL_PARAMETER(VR_KP, "kp", NULL, 1, "proportional gain"),
    REAL_PARAMETER(VR_KI, "ki", "1/s", 1, "integral gain"),
    REAL_PARAMETER(VR_INTEGRAL0, "integral0", NULL, 0, "initial value of the integral"),
};

static const unsigned state_vrs[] = {VR_INTEGRAL};

static double error(const double *v)
{
    return v[VR_SETPOINT] - v[VR_MEASUREMENT];
}

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_INTEGRAL0];
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    (void)x;
    dx[0] = error(v);
}

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    v[VR_INTEGRAL] = x[0];
    v[VR_DER_INTEGRAL] = error(v);
    v[VR_U] = v[VR_KP] * error(v) + v[VR_KI] * x[0];
}

/* u = kp (setpoint - measurement) + ki x: the integral is a state, held fixed. */
static double partial_derivative(const double *v, const double *x, unsigned output,
                                 unsigned input)
{
    (void)x;
    if (output != VR_U)
        return 0.0;
    return input == VR_SETPOINT ? v[VR_KP] : input == VR_MEASUREMENT ? -v[VR_KP] : 0.0;
}

const model_definition fmu_model = {
    .name = "PIController",
    .description = "Proportional-integral controller (PIController.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 1,
    .state_vrs = state_vrs,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
    .partial_derivative = partial_derivative,
};
