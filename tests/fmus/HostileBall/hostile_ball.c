/* A test model (never installed): the bouncing ball of FMUSDK's example, quirks included, for
 * the Model Exchange tests. h' = v, v' = -g; at the bounce (indicator h falls through 0)
 * v := -e v and h := -residue: like FMUSDK's ball, it leaves its indicator a hair below zero
 * after the bounce, so the ball's rise crosses it again (upwards) about residue / v later.
 * That crossing is the bounce's residue, not a new bounce. From nan_time on (negative: never)
 * der(v) is NaN: an integrator can make nothing of it. */
#include <math.h>

#include "model.h"

enum { VR_H, VR_V, VR_DER_H, VR_DER_V, VR_G, VR_E, VR_H0, VR_RESIDUE, VR_NAN_TIME,
       VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_H, "h", "m", "height above the floor", DEPENDS(VR_H), DEPENDS(VR_H0)),
    REAL_OUTPUT(VR_V, "v", "m/s", "vertical velocity, up positive", DEPENDS(VR_V), DEPENDS_NONE),
    REAL_DERIVATIVE(VR_DER_H, "der(h)", "m/s", "derivative of h", VR_H, DEPENDS(VR_V),
                    DEPENDS_NONE),
    REAL_DERIVATIVE(VR_DER_V, "der(v)", "m/s2", "derivative of v", VR_V, DEPENDS_NONE,
                    DEPENDS(VR_G)),
    REAL_PARAMETER(VR_G, "g", "m/s2", 9.81, "gravitational acceleration"),
    REAL_PARAMETER(VR_E, "e", NULL, 0.7, "coefficient of restitution"),
    REAL_PARAMETER(VR_H0, "h0", "m", 1, "initial height"),
    REAL_PARAMETER(VR_RESIDUE, "residue", "m", 4e-14,
                   "how far below the floor the bounce leaves the ball"),
    REAL_PARAMETER(VR_NAN_TIME, "nan_time", "s", -1,
                   "from this time on der(v) is NaN (negative: never)"),
};

static const unsigned state_vrs[] = {VR_H, VR_V};

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_H0];
    x[1] = 0.0;
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    int poisoned = v[VR_NAN_TIME] >= 0.0 && t >= v[VR_NAN_TIME];
    dx[0] = x[1];
    dx[1] = poisoned ? NAN : -v[VR_G];
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
    (void)v, (void)t;
    z[0] = x[0];
}

static void handle_events(double *v, double t, double *x, const int *fired)
{
    (void)t;
    if (fired[0]) {
        x[0] = -v[VR_RESIDUE];
        x[1] = -v[VR_E] * x[1];
    }
}

const model_definition fmu_model = {
    .name = "HostileBall",
    .description = "FMUSDK's bouncing ball with its event residue, der(v) NaN on request (a "
                   "test model)",
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
