/* SampledSignal.mo: a continuous state that decays, x' = -x / tau, sampled and held by a
 * periodic input clock (FMI 3.0 only): at tick k (t_k = k T) the clocked output y takes x(t_k)
 * and `ticks` counts the tick, both held until the next tick. Nothing continuous depends on the
 * clock, so an importer that never ticks it still integrates x alike; y shows where it ticked. */
#include "model.h"

enum { VR_X, VR_DER_X, VR_Y, VR_TICKS, VR_X0, VR_TAU, VARIABLE_COUNT };

enum { CLOCK_SAMPLE, CLOCK_COUNT };

static const model_clock clocks[CLOCK_COUNT] = {
    [CLOCK_SAMPLE] = {.name = "sample",
                      .description = "the sample clock: y takes x at its ticks",
                      .interval = 0.1},
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_X, "x", NULL, "the decaying state", DEPENDS(VR_X), DEPENDS(VR_X0)),
    REAL_DERIVATIVE(VR_DER_X, "der(x)", NULL, "-x / tau", VR_X, DEPENDS(VR_X),
                    DEPENDS(VR_X0, VR_TAU)),
    REAL_CLOCKED_OUTPUT(VR_Y, "y", NULL, 0, "x at the last tick, held between ticks",
                        CLOCK_SAMPLE, DEPENDS(VR_X)),
    REAL_CLOCKED_OUTPUT(VR_TICKS, "ticks", NULL, 0, "how many times the clock ticked",
                        CLOCK_SAMPLE, DEPENDS_NONE),
    REAL_PARAMETER(VR_X0, "x0", NULL, 1, "x at the start time"),
    REAL_PARAMETER(VR_TAU, "tau", "s", 0.5, "time constant of the decay"),
};

static const unsigned state_vrs[] = {VR_X};

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_X0];
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    dx[0] = -x[0] / v[VR_TAU];
}

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    v[VR_X] = x[0];
    v[VR_DER_X] = -x[0] / v[VR_TAU];
}

/* v holds the outputs at the tick's time and state (the framework refreshes them first) */
static void clock_tick(double *v, double t, const int *active)
{
    (void)t;
    if (!active[CLOCK_SAMPLE])
        return;
    v[VR_Y] = v[VR_X];
    v[VR_TICKS] += 1.0;
}

const model_definition fmu_model = {
    .name = "SampledSignal",
    .description = "A decaying state sampled and held by a periodic clock (SampledSignal.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 1,
    .state_vrs = state_vrs,
    .default_stop_time = 1.0,
    .default_step_size = 0.1,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
    .clocks = clocks,
    .n_clocks = CLOCK_COUNT,
    .clock_tick = clock_tick,
};
