/* BouncingBallContinuous.mo: free fall only. The master detects the floor (h = 0) as an
 * external event and applies the bounce by re-initializing the FMU with new h0 and v0, or by
 * restoring a state. */
#include "model.h"

enum { VR_H, VR_V, VR_DER_H, VR_DER_V, VR_G, VR_H0, VR_V0, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_H, "h", "m", "height above the floor", DEPENDS(VR_H), DEPENDS(VR_H0)),
    REAL_OUTPUT(VR_V, "v", "m/s", "vertical velocity, up positive", DEPENDS(VR_V), DEPENDS(VR_V0)),
    REAL_DERIVATIVE(VR_DER_H, "der(h)", "m/s", "derivative of h", VR_H, DEPENDS(VR_V),
                    DEPENDS(VR_V0)),
    REAL_DERIVATIVE(VR_DER_V, "der(v)", "m/s2", "derivative of v", VR_V, DEPENDS_NONE,
                    DEPENDS(VR_G)),
    REAL_PARAMETER(VR_G, "g", "m/s2", 9.81, "gravitational acceleration"),
    REAL_PARAMETER(VR_H0, "h0", "m", 1, "initial height"),
    REAL_PARAMETER(VR_V0, "v0", "m/s", 0, "initial velocity"),
};

static const unsigned state_vrs[] = {VR_H, VR_V};

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_H0];
    x[1] = v[VR_V0];
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    dx[0] = x[1];
    dx[1] = -v[VR_G];
}

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    v[VR_H] = x[0];
    v[VR_V] = x[1];
    v[VR_DER_H] = x[1];
    v[VR_DER_V] = -v[VR_G];
}

const model_definition fmu_model = {
    .name = "BouncingBallContinuous",
    .description = "Free-falling ball; the master handles the bounce (BouncingBallContinuous.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 2,
    .state_vrs = state_vrs,
    .n_event_indicators = 0,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
};
