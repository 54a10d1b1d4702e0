/* TorsionSpring.mo: a spring-damper between two bodies, outputs computed from the inputs only. */
#include "model.h"

enum {
    VR_TAU1, VR_TAU2, VR_THETA1, VR_THETA2, VR_OMEGA1, VR_OMEGA2, VR_K, VR_D,
    VARIABLE_COUNT
};

/* Both torques depend on the same inputs and parameters. */
#define TORQUE(vr, name, description)                                                          \
    REAL_OUTPUT(vr, name, "N.m", description, DEPENDS(VR_THETA1, VR_THETA2, VR_OMEGA1, VR_OMEGA2), \
                DEPENDS(VR_THETA1, VR_THETA2, VR_OMEGA1, VR_OMEGA2, VR_K, VR_D))

static const model_variable variables[VARIABLE_COUNT] = {
    TORQUE(VR_TAU1, "tau1", "torque on body 1"),
    TORQUE(VR_TAU2, "tau2", "torque on body 2"),
    REAL_INPUT(VR_THETA1, "theta1", "rad", 0, "angle of body 1"),
    REAL_INPUT(VR_THETA2, "theta2", "rad", 0, "angle of body 2"),
    REAL_INPUT(VR_OMEGA1, "omega1", "rad/s", 0, "angular velocity of body 1"),
    REAL_INPUT(VR_OMEGA2, "omega2", "rad/s", 0, "angular velocity of body 2"),
    REAL_PARAMETER(VR_K, "k", "N.m/rad", 100, "stiffness"),
    REAL_PARAMETER(VR_D, "d", "N.m.s/rad", 1, "damping"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    (void)x;
    v[VR_TAU1] = -v[VR_K] * (v[VR_THETA1] - v[VR_THETA2]) - v[VR_D] * (v[VR_OMEGA1] - v[VR_OMEGA2]);
    v[VR_TAU2] = -v[VR_TAU1];
}

/* tau1 = -k (theta1 - theta2) - d (omega1 - omega2) and tau2 = -tau1: linear in the inputs. */
static double partial_derivative(const double *v, const double *x, unsigned output,
                                 unsigned input)
{
    (void)x;
    double d_tau1 = input == VR_THETA1 ? -v[VR_K]
                    : input == VR_THETA2 ? v[VR_K]
                    : input == VR_OMEGA1 ? -v[VR_D]
                    : input == VR_OMEGA2 ? v[VR_D]
                                         : 0.0;
    return output == VR_TAU1 ? d_tau1 : output == VR_TAU2 ? -d_tau1 : 0.0;
}

const model_definition fmu_model = {
    .name = "TorsionSpring",
    .description = "Spring-damper between two rotating bodies (TorsionSpring.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
    .partial_derivative = partial_derivative,
};
