/* A test model (never installed): x' = -x from x(0) = 1 with one event indicator, x - 1/2,
 * which crosses at t = ln 2; with poison = 1 the indicator is NaN while x stays finite. The
 * event changes nothing: it is there to be found. */
#include <math.h>

#include "model.h"

enum { VR_X, VR_DER_X, VR_POISON, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_X, "x", "m", "decaying state", DEPENDS(VR_X), DEPENDS_NONE),
    REAL_DERIVATIVE(VR_DER_X, "der(x)", "m/s", "derivative of x", VR_X, DEPENDS(VR_X),
                    DEPENDS_NONE),
    REAL_PARAMETER(VR_POISON, "poison", "-", 0, "1: the event indicator is NaN"),
};

static const unsigned state_vrs[] = {VR_X};

static void initial_states(const double *v, double *x)
{
    (void)v;
    x[0] = 1.0;
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)v, (void)t;
    dx[0] = -x[0];
}

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    v[VR_X] = x[0];
    v[VR_DER_X] = -x[0];
}

static void event_indicators(const double *v, double t, const double *x, double *z)
{
    (void)t;
    z[0] = v[VR_POISON] != 0.0 ? NAN : x[0] - 0.5;
}

static void handle_events(double *v, double t, double *x, const int *fired)
{
    (void)v, (void)t, (void)x, (void)fired;
}

const model_definition fmu_model = {
    .name = "NanIndicator",
    .description = "x' = -x with an event indicator x - 1/2, NaN on request (a test model)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 1,
    .state_vrs = state_vrs,
    .n_event_indicators = 1,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
    .event_indicators = event_indicators,
    .handle_events = handle_events,
};
