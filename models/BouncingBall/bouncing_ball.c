/* BouncingBall.mo: free fall with the bounce as an internal event, v := -e v at h = 0.
 * A rebound lower than gap_tol ends with the ball at rest, so the infinitely many bounces of
 * an ideal ball (all within finite time) do not stall the integrator. */
#include "model.h"

enum {
    VR_H, VR_V, VR_DER_H, VR_DER_V, VR_G, VR_E, VR_H0, VR_V0, VR_GAP_TOL,
    VARIABLE_COUNT
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_H, "h", "m", "height above the floor", DEPENDS(VR_H), DEPENDS(VR_H0)),
    REAL_OUTPUT(VR_V, "v", "m/s", "vertical velocity, up positive", DEPENDS(VR_V), DEPENDS(VR_V0)),
    REAL_DERIVATIVE(VR_DER_H, "der(h)", "m/s", "derivative of h", VR_H, DEPENDS(VR_H, VR_V),
                    DEPENDS(VR_H0, VR_V0)),
    REAL_DERIVATIVE(VR_DER_V, "der(v)", "m/s2", "derivative of v", VR_V, DEPENDS(VR_H, VR_V),
                    DEPENDS(VR_H0, VR_V0, VR_G)),
    REAL_PARAMETER(VR_G, "g", "m/s2", 9.81, "gravitational acceleration"),
    REAL_PARAMETER(VR_E, "e", NULL, 0.8, "coefficient of restitution"),
    REAL_PARAMETER(VR_H0, "h0", "m", 1, "initial height"),
    REAL_PARAMETER(VR_V0, "v0", "m/s", 0, "initial velocity"),
    REAL_PARAMETER(VR_GAP_TOL, "gap_tol", "m", 1e-6,
              "a rebound lower than this ends with the ball at rest on the floor"),
};

static const unsigned state_vrs[] = {VR_H, VR_V};

static int resting(const double *x)
{
    return x[0] <= 0.0 && x[1] == 0.0;
}

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_H0];
    x[1] = v[VR_V0];
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    int still = resting(x);
    dx[0] = x[1];
    dx[1] = still ? 0.0 : -v[VR_G];
}

static void outputs(double *v, double t, const double *x)
{
    double dx[2];
    derivatives(v, t, x, dx);
    v[VR_H] = x[0];
    v[VR_V] = x[1];
    v[VR_DER_H] = dx[0];
    v[VR_DER_V] = dx[1];
}

static void event_indicators(const double *v, double t, const double *x, double *z)
{
    (void)v;
    (void)t;
    z[0] = x[0];
}

static void handle_events(double *v, double t, double *x, const int *fired)
{
    (void)t;
    if (!fired[0])
        return;
    double rebound = -v[VR_E] * x[1];
    x[0] = 0.0;
    x[1] = rebound * rebound <= 2.0 * v[VR_G] * v[VR_GAP_TOL] ? 0.0 : rebound;
}

const model_definition fmu_model = {
    .name = "BouncingBall",
    .description = "Ball bouncing on a floor, the bounce an internal event (BouncingBall.mo)",
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
