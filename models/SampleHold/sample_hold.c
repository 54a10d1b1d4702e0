/* SampleHold.mo: a cosine sampled every hold_step from t = 0 and held in between, the way an
 * FMU with a fixed internal step shows its outputs: piecewise constant in the master's time.
 * The held output falls through zero at the first sample at or after the cosine's zero
 * 1 / (4 f), so an event on it is known exactly. */
#include <math.h>

#include "model.h"

/* C11 without POSIX has no M_PI */
static const double PI = 3.14159265358979323846;

enum { VR_Y, VR_AMPLITUDE, VR_FREQUENCY, VR_HOLD_STEP, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_DISCRETE_OUTPUT(VR_Y, "y", NULL,
                         "amplitude * cos(2 pi f t_k), t_k the last sample instant", DEPENDS_NONE,
                         DEPENDS(VR_AMPLITUDE, VR_FREQUENCY, VR_HOLD_STEP)),
    REAL_PARAMETER(VR_AMPLITUDE, "amplitude", NULL, 1, "amplitude of the cosine"),
    REAL_PARAMETER(VR_FREQUENCY, "f", "1/s", 0.7, "frequency of the cosine"),
    REAL_PARAMETER(VR_HOLD_STEP, "hold_step", "s", 1e-3, "time between two samples"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)x;
    double sample = floor(t / v[VR_HOLD_STEP]) * v[VR_HOLD_STEP];
    v[VR_Y] = v[VR_AMPLITUDE] * cos(2.0 * PI * v[VR_FREQUENCY] * sample);
}

/* The next sample instant: y changes there. */
static double next_time_event(const double *v, double t)
{
    double h = v[VR_HOLD_STEP];
    double next = (floor(t / h) + 1.0) * h;
    /* t / h may round to just below an integer when t is itself a sample instant */
    return next > t ? next : next + h;
}

const model_definition fmu_model = {
    .name = "SampleHold",
    .description = "Cosine sampled and held every hold_step (SampleHold.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-2,
    .outputs = outputs,
    .next_time_event = next_time_event,
};
