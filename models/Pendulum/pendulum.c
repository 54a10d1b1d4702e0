/* Pendulum.mo: a rigid pendulum driven by a torque at the pivot, no events. */
#include <math.h>

#include "model.h"

enum {
    VR_THETA, VR_OMEGA, VR_ALPHA, VR_DER_THETA, VR_TORQUE,
    VR_M, VR_L, VR_THETA0, VR_OMEGA0, VR_G, VR_INERTIA,
    VARIABLE_COUNT
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_THETA, "theta", "rad", "angle from the downward vertical", DEPENDS(VR_THETA),
                DEPENDS(VR_THETA0)),
    REAL_OUTPUT(VR_OMEGA, "omega", "rad/s", "angular velocity", DEPENDS(VR_OMEGA),
                DEPENDS(VR_OMEGA0)),
    REAL_DERIVATIVE_OUTPUT(VR_ALPHA, "alpha", "rad/s2", "angular acceleration der(omega)", VR_OMEGA,
                           DEPENDS(VR_THETA, VR_TORQUE),
                           DEPENDS(VR_TORQUE, VR_M, VR_L, VR_THETA0, VR_G, VR_INERTIA)),
    REAL_DERIVATIVE(VR_DER_THETA, "der(theta)", "rad/s", "derivative of theta", VR_THETA,
                    DEPENDS(VR_OMEGA), DEPENDS(VR_OMEGA0)),
    REAL_INPUT(VR_TORQUE, "torque", "N.m", 0, "torque at the pivot"),
    REAL_PARAMETER(VR_M, "m", "kg", 40, "mass"),
    REAL_PARAMETER(VR_L, "L", "m", 0.6, "distance from the pivot to the centre of mass"),
    REAL_PARAMETER(VR_THETA0, "theta0", "rad", 0, "initial angle"),
    REAL_PARAMETER(VR_OMEGA0, "omega0", "rad/s", 0, "initial angular velocity"),
    REAL_PARAMETER(VR_G, "g", "m/s2", 9.81, "gravitational acceleration"),
    REAL_PARAMETER(VR_INERTIA, "inertia", "kg.m2", 20, "moment of inertia about the pivot"),
};

static const unsigned state_vrs[] = {VR_THETA, VR_OMEGA};

static double angular_acceleration(const double *v, double theta)
{
    return -(v[VR_M] * v[VR_G] * v[VR_L] / v[VR_INERTIA]) * sin(theta) +
           v[VR_TORQUE] / v[VR_INERTIA];
}

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_THETA0];
    x[1] = v[VR_OMEGA0];
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    dx[0] = x[1];
    dx[1] = angular_acceleration(v, x[0]);
}

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    v[VR_THETA] = x[0];
    v[VR_OMEGA] = x[1];
    v[VR_DER_THETA] = x[1];
    v[VR_ALPHA] = angular_acceleration(v, x[0]);
}

/* theta and omega are states; alpha moves with the torque by 1 / inertia. */
static double partial_derivative(const double *v, const double *x, unsigned output,
                                 unsigned input)
{
    (void)x;
    return output == VR_ALPHA && input == VR_TORQUE ? 1.0 / v[VR_INERTIA] : 0.0;
}

const model_definition fmu_model = {
    .name = "Pendulum",
    .description = "Rigid pendulum with a torque input (Pendulum.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 2,
    .state_vrs = state_vrs,
    .n_event_indicators = 0,
    .default_stop_time = 3.0,
    .default_step_size = 1e-3,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
    .partial_derivative = partial_derivative,
};
