/* Timer.mo: an alarm on a countdown clock. At initialization the timer announces its first
 * alarm `delay` seconds ahead; at each alarm it counts it and announces the next one `growth`
 * times further ahead than the last, so with delay 0.1 and growth 2 the alarms ring at 0.1,
 * 0.3, 0.7 and 1.5 s. The clocked outputs change at the alarms only. */
#include "model.h"

enum { VR_COUNT, VR_LAST_ALARM, VR_NEXT_INTERVAL, VR_ANNOUNCED, VR_DELAY, VR_GROWTH,
       VARIABLE_COUNT };

enum { CLOCK_ALARM, CLOCK_COUNT };

static const model_clock clocks[CLOCK_COUNT] = {
    [CLOCK_ALARM] = {.name = "alarm",
                     .description = "rings when the announced interval has passed",
                     .kind = CLOCK_COUNTDOWN},
};

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_CLOCKED_OUTPUT(VR_COUNT, "count", NULL, 0, "alarms so far", CLOCK_ALARM, DEPENDS_NONE),
    REAL_CLOCKED_OUTPUT(VR_LAST_ALARM, "last_alarm", "s", -1,
                        "time of the last alarm (-1 before the first)", CLOCK_ALARM,
                        DEPENDS_NONE),
    REAL_CLOCKED_LOCAL(VR_NEXT_INTERVAL, "next_interval", "s", 0,
                       "interval to the next alarm (0: delay)", CLOCK_ALARM),
    REAL_CLOCKED_LOCAL(VR_ANNOUNCED, "announced", NULL, 0,
                       "1 once the next alarm's interval was announced", CLOCK_ALARM),
    REAL_PARAMETER(VR_DELAY, "delay", "s", 0.1, "interval to the first alarm"),
    REAL_PARAMETER(VR_GROWTH, "growth", NULL, 2, "each interval over the one before"),
};

/* nothing moves between alarms */
static void outputs(double *v, double t, const double *x)
{
    (void)v;
    (void)t;
    (void)x;
}

static void clock_tick(double *v, double t, const int *active)
{
    if (!active[CLOCK_ALARM])
        return;
    v[VR_COUNT] += 1.0;
    v[VR_LAST_ALARM] = t;
    v[VR_NEXT_INTERVAL] = v[VR_GROWTH] * v[VR_NEXT_INTERVAL];
    v[VR_ANNOUNCED] = 0.0;
}

static double clock_interval(double *v, size_t clock, int *changed)
{
    (void)clock;
    if (v[VR_NEXT_INTERVAL] == 0.0)
        v[VR_NEXT_INTERVAL] = v[VR_DELAY];
    *changed = v[VR_ANNOUNCED] == 0.0;
    v[VR_ANNOUNCED] = 1.0;
    return v[VR_NEXT_INTERVAL];
}

const model_definition fmu_model = {
    .name = "Timer",
    .description = "An alarm on a countdown clock, each interval growth times the last "
                   "(Timer.mo)",
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
