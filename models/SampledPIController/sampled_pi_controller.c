/* SampledPIController.mo: a PI controller sampled by a periodic input clock (FMI 3.0 only).
 * At each tick k the error e_k = setpoint - measurement is sampled and
 *   u_k = kp e_k + ki I_k,   I_{k+1} = I_k + T e_k   (T the clock's interval),
 * so u is a clocked output, constant between ticks. No continuous states: nothing moves
 * between ticks whatever the importer's steps. */
#include "model.h"

enum { VR_U, VR_INTEGRAL, VR_SETPOINT, VR_MEASUREMENT, VR_KP, VR_KI, VARIABLE_COUNT };

enum { CLOCK_SAMPLE, CLOCK_COUNT };

static const model_clock clocks[CLOCK_COUNT] = {
    [CLOCK_SAMPLE] = {.name = "sample",
                      .description = "the sample clock: the controller acts at its ticks",
                      .interval = 0.1},
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_CLOCKED_OUTPUT(VR_U, "u", NULL, 0, "controller output, held between ticks",
                        CLOCK_SAMPLE, DEPENDS(VR_SETPOINT, VR_MEASUREMENT)),
    REAL_CLOCKED_LOCAL(VR_INTEGRAL, "integral", "s", 0,
                       "sum of T e over the ticks so far: the next tick's integral", CLOCK_SAMPLE),
    REAL_INPUT(VR_SETPOINT, "setpoint", NULL, 0, "reference value, sampled at the ticks"),
    REAL_INPUT(VR_MEASUREMENT, "measurement", NULL, 0, "measured value, sampled at the ticks"),
    REAL_PARAMETER(VR_KP, "kp", NULL, 1, "proportional gain"),
    REAL_PARAMETER(VR_KI, "ki", "1/s", 1, "integral gain"),
};

/* u depends on nothing continuous: the inputs act only through the ticks */
static void outputs(double *v, double t, const double *x)
{
    (void)v;
    (void)t;
    (void)x;
}

static void clock_tick(double *v, double t, const int *active)
{
    (void)t;
    if (!active[CLOCK_SAMPLE])
        return;
    double error = v[VR_SETPOINT] - v[VR_MEASUREMENT];
    v[VR_U] = v[VR_KP] * error + v[VR_KI] * v[VR_INTEGRAL];
    v[VR_INTEGRAL] += clocks[CLOCK_SAMPLE].interval * error;
}

const model_definition fmu_model = {
    .name = "SampledPIController",
    .description = "PI controller sampled by a periodic clock (SampledPIController.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 2.0,
    .default_step_size = 0.1,
    .outputs = outputs,
    .clocks = clocks,
    .n_clocks = CLOCK_COUNT,
    .clock_tick = clock_tick,
};
