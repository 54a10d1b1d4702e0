/* PreloadedSpring.mo: a torsion spring whose torque is a state, set from the angle input only
 * when the FMU leaves initialization mode, as 20-sim's exports compute their initial values
 * (maestro's MassSpringDamper2): tau(0) = -k (angle(0) - angle0), then tau' = -k omega. A master
 * that sets the connected inputs inside initialization mode starts it at the spring's real
 * preload; one that sets them afterwards starts it from the angle input's start value. */
#include "model.h"

enum { VR_TAU, VR_DER_TAU, VR_ANGLE, VR_OMEGA, VR_K, VR_ANGLE0, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_TAU, "tau", "N.m", "spring torque", DEPENDS(VR_TAU),
                DEPENDS(VR_ANGLE, VR_K, VR_ANGLE0)),
    REAL_DERIVATIVE(VR_DER_TAU, "der(tau)", NULL, "-k omega (N.m/s)", VR_TAU, DEPENDS(VR_OMEGA),
                    DEPENDS(VR_OMEGA, VR_K)),
    REAL_INPUT(VR_ANGLE, "angle", "rad", 0, "angle, read when initialization ends"),
    REAL_INPUT(VR_OMEGA, "omega", "rad/s", 0, "angular velocity, integrated into the torque"),
    REAL_PARAMETER(VR_K, "k", "N.m/rad", 100, "stiffness"),
    REAL_PARAMETER(VR_ANGLE0, "angle0", "rad", 0.1, "unloaded angle"),
};

static const unsigned state_vrs[] = {VR_TAU};

static void initial_states(const double *v, double *x)
{
    x[0] = -v[VR_K] * (v[VR_ANGLE] - v[VR_ANGLE0]);
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    (void)x;
    dx[0] = -v[VR_K] * v[VR_OMEGA];
}

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    v[VR_TAU] = x[0];
    v[VR_DER_TAU] = -v[VR_K] * v[VR_OMEGA];
}

const model_definition fmu_model = {
    .name = "PreloadedSpring",
    .description = "Spring torque set from the angle input when initialization ends "
                   "(PreloadedSpring.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 1,
    .state_vrs = state_vrs,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
};
