/* PendulumDiscreteContact.mo: the pendulum of Pendulum.mo bouncing off a wall. The impact is an
 * internal event: omega := -restitution * omega, theta := theta_wall. A rebound too weak to
 * leave the contact band gap_tol ends at rest against the wall, which keeps a wall that gravity
 * pushes into from chattering. */
#include <math.h>

#include "model.h"

enum {
    VR_THETA, VR_OMEGA, VR_ALPHA, VR_DER_THETA, VR_CONTACT, VR_TORQUE,
    VR_M, VR_L, VR_THETA0, VR_OMEGA0, VR_G, VR_INERTIA,
    VR_THETA_WALL, VR_SENSE, VR_RESTITUTION, VR_GAP_TOL,
    VARIABLE_COUNT
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_THETA, "theta", "rad", "angle from the downward vertical", DEPENDS(VR_THETA),
                DEPENDS(VR_THETA0)),
    REAL_OUTPUT(VR_OMEGA, "omega", "rad/s", "angular velocity", DEPENDS(VR_OMEGA),
                DEPENDS(VR_OMEGA0)),
    REAL_DERIVATIVE_OUTPUT(VR_ALPHA, "alpha", "rad/s2", "angular acceleration der(omega)", VR_OMEGA,
                           DEPENDS(VR_THETA, VR_OMEGA, VR_TORQUE),
                           DEPENDS(VR_TORQUE, VR_M, VR_L, VR_THETA0, VR_OMEGA0, VR_G, VR_INERTIA,
                                   VR_THETA_WALL, VR_SENSE)),
    REAL_DERIVATIVE(VR_DER_THETA, "der(theta)", "rad/s", "derivative of theta", VR_THETA,
                    DEPENDS(VR_THETA, VR_OMEGA, VR_TORQUE),
                    DEPENDS(VR_TORQUE, VR_M, VR_L, VR_THETA0, VR_OMEGA0, VR_G, VR_INERTIA,
                            VR_THETA_WALL, VR_SENSE)),
    BOOLEAN_DISCRETE_OUTPUT(VR_CONTACT, "contact", "the pendulum touches the wall (within gap_tol)",
                            DEPENDS(VR_THETA), DEPENDS(VR_THETA0, VR_THETA_WALL, VR_GAP_TOL)),
    REAL_INPUT(VR_TORQUE, "torque", "N.m", 0, "torque at the pivot"),
    REAL_PARAMETER(VR_M, "m", "kg", 40, "mass"),
    REAL_PARAMETER(VR_L, "L", "m", 0.6, "distance from the pivot to the centre of mass"),
    REAL_PARAMETER(VR_THETA0, "theta0", "rad", 0, "initial angle"),
    REAL_PARAMETER(VR_OMEGA0, "omega0", "rad/s", 0, "initial angular velocity"),
    REAL_PARAMETER(VR_G, "g", "m/s2", 9.81, "gravitational acceleration"),
    REAL_PARAMETER(VR_INERTIA, "inertia", "kg.m2", 20, "moment of inertia about the pivot"),
    REAL_PARAMETER(VR_THETA_WALL, "theta_wall", "rad", 0, "angle of the wall"),
    INTEGER_PARAMETER(VR_SENSE, "sense", -1,
                      "-1: the wall is hit while theta decreases, +1: while it increases"),
    REAL_PARAMETER(VR_RESTITUTION, "restitution", NULL, 1,
              "omega after an impact is -restitution times omega before"),
    REAL_PARAMETER(VR_GAP_TOL, "gap_tol", "rad", 1e-6,
              "contact band; a rebound that would not leave it ends at rest against the wall"),
};

static const unsigned state_vrs[] = {VR_THETA, VR_OMEGA};

static double sense(const double *v)
{
    return v[VR_SENSE] < 0 ? -1.0 : 1.0;
}

static double free_acceleration(const double *v, double theta)
{
    return -(v[VR_M] * v[VR_G] * v[VR_L] / v[VR_INERTIA]) * sin(theta) +
           v[VR_TORQUE] / v[VR_INERTIA];
}

/* Positive on the free side of the wall, zero at the wall. */
static double gap(const double *v, const double *x)
{
    return -sense(v) * (x[0] - v[VR_THETA_WALL]);
}

/* Resting against the wall: at the wall, still, and pushed into it. */
static int resting(const double *v, const double *x)
{
    return gap(v, x) <= 0.0 && x[1] == 0.0 && sense(v) * free_acceleration(v, x[0]) >= 0.0;
}

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_THETA0];
    x[1] = v[VR_OMEGA0];
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    int still = resting(v, x);
    dx[0] = still ? 0.0 : x[1];
    dx[1] = still ? 0.0 : free_acceleration(v, x[0]);
}

static void outputs(double *v, double t, const double *x)
{
    double dx[2];
    derivatives(v, t, x, dx);
    v[VR_THETA] = x[0];
    v[VR_OMEGA] = x[1];
    v[VR_DER_THETA] = dx[0];
    v[VR_ALPHA] = dx[1];
    v[VR_CONTACT] = fabs(x[0] - v[VR_THETA_WALL]) <= v[VR_GAP_TOL] ? 1.0 : 0.0;
}

static void event_indicators(const double *v, double t, const double *x, double *z)
{
    (void)t;
    z[0] = gap(v, x);
}

static void handle_events(double *v, double t, double *x, const int *fired)
{
    (void)t;
    if (!fired[0])
        return;
    double rebound = -v[VR_RESTITUTION] * x[1];
    double push = fmax(sense(v) * free_acceleration(v, v[VR_THETA_WALL]), 0.0);
    x[0] = v[VR_THETA_WALL];
    x[1] = rebound * rebound <= 2.0 * push * v[VR_GAP_TOL] ? 0.0 : rebound;
}

const model_definition fmu_model = {
    .name = "PendulumDiscreteContact",
    .description = "Pendulum bouncing off a wall, the impact an internal event "
                   "(PendulumDiscreteContact.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 2,
    .state_vrs = state_vrs,
    .n_event_indicators = 1,
    .default_stop_time = 3.0,
    .default_step_size = 1e-3,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
    .event_indicators = event_indicators,
    .handle_events = handle_events,
};
