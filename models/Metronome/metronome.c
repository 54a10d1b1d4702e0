/* Metronome.mo: beats on a changing clock. It announces the interval `period` at the start;
 * after `faster_after` beats it announces half of it, so with period 0.2 and 3 beats the beats
 * come at 0.2, 0.4, 0.6, then 0.7, 0.8, 0.9, ... s. The clocked outputs change at the beats
 * only. */
#include "model.h"

enum { VR_COUNT, VR_LAST_BEAT, VR_INTERVAL, VR_ANNOUNCED, VR_PERIOD, VR_FASTER_AFTER,
       VARIABLE_COUNT };

enum { CLOCK_BEAT, CLOCK_COUNT };

static const model_clock clocks[CLOCK_COUNT] = {
    [CLOCK_BEAT] = {.name = "beat",
                    .description = "beats every announced interval",
                    .kind = CLOCK_CHANGING},
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_CLOCKED_OUTPUT(VR_COUNT, "count", NULL, 0, "beats so far", CLOCK_BEAT, DEPENDS_NONE),
    REAL_CLOCKED_OUTPUT(VR_LAST_BEAT, "last_beat", "s", -1,
                        "time of the last beat (-1 before the first)", CLOCK_BEAT,
                        DEPENDS_NONE),
    REAL_CLOCKED_LOCAL(VR_INTERVAL, "interval", "s", 0,
                       "interval between beats (0: period)", CLOCK_BEAT),
    REAL_CLOCKED_LOCAL(VR_ANNOUNCED, "announced", NULL, 0,
                       "1 once the interval was announced", CLOCK_BEAT),
    REAL_PARAMETER(VR_PERIOD, "period", "s", 0.2, "interval between the first beats"),
    REAL_PARAMETER(VR_FASTER_AFTER, "faster_after", NULL, 3,
                   "beats after which the interval is halved"),
};

/* nothing moves between beats */
static void outputs(double *v, double t, const double *x)
{
    (void)v;
    (void)t;
    (void)x;
}

static void clock_tick(double *v, double t, const int *active)
{
    if (!active[CLOCK_BEAT])
        return;
    v[VR_COUNT] += 1.0;
    v[VR_LAST_BEAT] = t;
    if (v[VR_COUNT] == v[VR_FASTER_AFTER]) {
        v[VR_INTERVAL] = 0.5 * v[VR_INTERVAL];
        v[VR_ANNOUNCED] = 0.0;
    }
}

static double clock_interval(double *v, size_t clock, int *changed)
{
    (void)clock;
    if (v[VR_INTERVAL] == 0.0)
        v[VR_INTERVAL] = v[VR_PERIOD];
    *changed = v[VR_ANNOUNCED] == 0.0;
    v[VR_ANNOUNCED] = 1.0;
    return v[VR_INTERVAL];
}

const model_definition fmu_model = {
    .name = "Metronome",
    .description = "Beats on a changing clock, twice as fast after a few beats (Metronome.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 2.0,
    .default_step_size = 0.1,
    .outputs = outputs,
    .clocks = clocks,
    .n_clocks = CLOCK_COUNT,
    .clock_tick = clock_tick,
    .clock_interval = clock_interval,
};
