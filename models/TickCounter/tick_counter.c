/* TickCounter.mo: counts the ticks of its triggered input clock `tick` and remembers when the
 * last one came: both clocked outputs change at the ticks only. */
#include "model.h"

enum { VR_COUNT, VR_LAST_TICK, VR_SAMPLED, VR_SIGNAL, VARIABLE_COUNT };

enum { CLOCK_TICK, CLOCK_COUNT };

static const model_clock clocks[CLOCK_COUNT] = {
    [CLOCK_TICK] = {.name = "tick",
                    .description = "the importer ticks it when it likes",
                    .kind = CLOCK_TRIGGERED},
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_CLOCKED_OUTPUT(VR_COUNT, "count", NULL, 0, "ticks so far", CLOCK_TICK, DEPENDS_NONE),
    REAL_CLOCKED_OUTPUT(VR_LAST_TICK, "last_tick", "s", -1,
                        "time of the last tick (-1 before the first)", CLOCK_TICK, DEPENDS_NONE),
    REAL_CLOCKED_OUTPUT(VR_SAMPLED, "sampled", NULL, 0, "signal sampled at the last tick",
                        CLOCK_TICK, DEPENDS(VR_SIGNAL)),
    REAL_INPUT(VR_SIGNAL, "signal", NULL, 0, "value sampled at each tick"),
};

/* nothing moves between ticks */
static void outputs(double *v, double t, const double *x)
{
    (void)v;
    (void)t;
    (void)x;
}

static void clock_tick(double *v, double t, const int *active)
{
    if (!active[CLOCK_TICK])
        return;
    v[VR_COUNT] += 1.0;
    v[VR_LAST_TICK] = t;
    v[VR_SAMPLED] = v[VR_SIGNAL];
}

const model_definition fmu_model = {
    .name = "TickCounter",
    .description = "Counts the ticks of a triggered input clock (TickCounter.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 0.1,
    .outputs = outputs,
    .clocks = clocks,
    .n_clocks = CLOCK_COUNT,
    .clock_tick = clock_tick,
};
