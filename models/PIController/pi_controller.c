/* PIController.mo: u = kp e + ki * integral(e), e = setpoint - measurement. Built with the
 * Euler back-end, which integrates the piecewise-constant error of a co-simulation exactly. */
#include "model.h"

enum {
    VR_U, VR_INTEGRAL, VR_DER_INTEGRAL, VR_SETPOINT, VR_MEASUREMENT, VR_KP, VR_KI, VR_INTEGRAL0,
    VARIABLE_COUNT
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_U, "u", NULL, "controller output",
                DEPENDS(VR_INTEGRAL, VR_SETPOINT, VR_MEASUREMENT),
                DEPENDS(VR_SETPOINT, VR_MEASUREMENT, VR_KP, VR_KI, VR_INTEGRAL0)),
    REAL_LOCAL(VR_INTEGRAL, "integral", NULL, "integral of the error", NULL, DEPENDS(VR_INTEGRAL0)),
    REAL_DERIVATIVE(VR_DER_INTEGRAL, "der(integral)", NULL, "the error setpoint - measurement",
                    VR_INTEGRAL, DEPENDS(VR_SETPOINT, VR_MEASUREMENT),
                    DEPENDS(VR_SETPOINT, VR_MEASUREMENT)),
    REAL_INPUT(VR_SETPOINT, "setpoint", NULL, 0, "reference value"),
    REAL_INPUT(VR_MEASUREMENT, "measurement", NULL, 0, "measured value"),
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
