/* SlidingMass.mo: a mass launched along a floor with Coulomb friction. It decelerates at
 * mu g until it stops; the stop is an internal event that sets v to exactly 0, where it stays.
 * An indicator on v then rests on zero: the case of an output that reaches zero and stays. */
#include "model.h"

enum { VR_X, VR_V, VR_DER_X, VR_DER_V, VR_MU, VR_G, VR_X0, VR_V0, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_X, "x", "m", "position along the floor", DEPENDS(VR_X), DEPENDS(VR_X0)),
    REAL_OUTPUT(VR_V, "v", "m/s", "velocity; exactly 0 once stopped", DEPENDS(VR_V),
                DEPENDS(VR_V0)),
    REAL_DERIVATIVE(VR_DER_X, "der(x)", "m/s", "derivative of x", VR_X, DEPENDS(VR_V),
                    DEPENDS(VR_V0)),
    REAL_DERIVATIVE(VR_DER_V, "der(v)", "m/s2", "derivative of v", VR_V, DEPENDS(VR_V),
                    DEPENDS(VR_V0, VR_MU, VR_G)),
    REAL_PARAMETER(VR_MU, "mu", NULL, 0.3, "coefficient of friction"),
    REAL_PARAMETER(VR_G, "g", "m/s2", 9.81, "gravitational acceleration"),
    REAL_PARAMETER(VR_X0, "x0", "m", 0, "initial position"),
    REAL_PARAMETER(VR_V0, "v0", "m/s", 2, "initial velocity (forward, > 0)"),
};

static const unsigned state_vrs[] = {VR_X, VR_V};

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_X0];
    x[1] = v[VR_V0];
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    dx[0] = x[1];
    /* once stopped, static friction holds the mass */
    dx[1] = x[1] > 0.0 ? -v[VR_MU] * v[VR_G] : 0.0;
}

static void outputs(double *v, double t, const double *x)
{
    double dx[2];
    derivatives(v, t, x, dx);
    v[VR_X] = x[0];
    v[VR_V] = x[1];
    v[VR_DER_X] = dx[0];
    v[VR_DER_V] = dx[1];
}

static void event_indicators(const double *v, double t, const double *x, double *z)
{
    (void)v;
    (void)t;
    z[0] = x[1];
}

static void handle_events(double *v, double t, double *x, const int *fired)
{
    (void)v;
    (void)t;
    if (fired[0]) {
        x[1] = 0.0;
    }
}

const model_definition fmu_model = {
    .name = "SlidingMass",
    .description = "Mass sliding with friction until it stops (SlidingMass.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 2,
    .state_vrs = state_vrs,
    .n_event_indicators = 1,
    .default_stop_time = 1.0,
    .default_step_size = 1e-2,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
    .event_indicators = event_indicators,
    .handle_events = handle_events,
};
