/* LevelDetector.mo: a tank filled at the rate `inflow`, emptied when its level reaches
 * `threshold`. The emptying is an internal event that ticks the output clock `full`; the
 * clocked output `count` (how many times the tank was full) changes at its ticks only. With a
 * constant inflow the ticks fall at k threshold / inflow, k = 1, 2, ... (level0 = 0). */
#include "model.h"

/* level_detector_step_end.c builds the tank without early return */
#ifndef LEVEL_DETECTOR_EVENTS_AT_STEP_END
#define LEVEL_DETECTOR_EVENTS_AT_STEP_END 0
#endif

enum { VR_LEVEL, VR_DER_LEVEL, VR_COUNT, VR_INFLOW, VR_THRESHOLD, VR_LEVEL0, VARIABLE_COUNT };

enum { CLOCK_FULL, CLOCK_COUNT };

static const model_clock clocks[CLOCK_COUNT] = {
    [CLOCK_FULL] = {.name = "full",
                    .description = "ticks when the level reaches the threshold",
                    .kind = CLOCK_OUTPUT,
                    .indicator = 0},
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_LEVEL, "level", "m", "level in the tank", DEPENDS(VR_LEVEL), DEPENDS(VR_LEVEL0)),
    REAL_DERIVATIVE(VR_DER_LEVEL, "der(level)", "m/s", "derivative of level", VR_LEVEL,
                    DEPENDS(VR_INFLOW), DEPENDS(VR_INFLOW)),
    REAL_CLOCKED_OUTPUT(VR_COUNT, "count", NULL, 0, "how many times the tank was full",
                        CLOCK_FULL, DEPENDS_NONE),
    REAL_INPUT(VR_INFLOW, "inflow", "m/s", 1, "rate at which the level rises"),
    REAL_PARAMETER(VR_THRESHOLD, "threshold", "m", 0.3, "level at which the tank is emptied"),
    REAL_PARAMETER(VR_LEVEL0, "level0", "m", 0, "initial level"),
};

static const unsigned state_vrs[] = {VR_LEVEL};

static void initial_states(const double *v, double *x)
{
    x[0] = v[VR_LEVEL0];
}

static void derivatives(const double *v, double t, const double *x, double *dx)
{
    (void)t;
    (void)x;
    dx[0] = v[VR_INFLOW];
}

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    v[VR_LEVEL] = x[0];
    v[VR_DER_LEVEL] = v[VR_INFLOW];
}

static void event_indicators(const double *v, double t, const double *x, double *z)
{
    (void)t;
    z[0] = v[VR_THRESHOLD] - x[0];
}

static void handle_events(double *v, double t, double *x, const int *fired)
{
    (void)t;
    if (!fired[0])
        return;
    x[0] = 0.0;
    v[VR_COUNT] += 1.0;
}

const model_definition fmu_model = {
    .name = "LevelDetector",
    .description = "Tank emptied at a threshold, an output clock ticking there "
                   "(LevelDetector.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .n_states = 1,
    .state_vrs = state_vrs,
    .n_event_indicators = 1,
    .events_at_step_end = LEVEL_DETECTOR_EVENTS_AT_STEP_END,
    .default_stop_time = 1.0,
    .default_step_size = 0.1,
    .initial_states = initial_states,
    .derivatives = derivatives,
    .outputs = outputs,
    .event_indicators = event_indicators,
    .handle_events = handle_events,
    .clocks = clocks,
    .n_clocks = CLOCK_COUNT,
};
