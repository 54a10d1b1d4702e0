/* FMI 3.0 output clocks and triggered input clocks in Co-Simulation, under AddressSanitizer
 * too: the tank of models/LevelDetector is full at 0.3, 0.6 and 0.9 (inflow 1, threshold 0.3)
 * and its output clock `full` ticks there, an own event of the tank (SSX_OWN_OUTPUT_CLOCK,
 * clock 1); connected to the triggered clock `tick` of models/TickCounter, each tick ticks the
 * counter where the master accepts the step that holds it. Connections that cannot tick are
 * refused naming why. The countdown clock of models/Timer rings at the intervals the FMU
 * announces (0.1, 0.3, 0.7 s), and a restored state brings back the alarms it had planned. */
#include <math.h>

#include "test_support.h"

/* models/LevelDetector/level_detector.c: level, count; its clock follows the Euler step size,
 * the time and the event indicator */
enum { TANK_LEVEL = 0, TANK_COUNT = 2, TANK_FULL = 9 };
/* models/TickCounter/tick_counter.c: count, last_tick, sampled, signal; then time, the clock */
enum { COUNTER_COUNT = 0, COUNTER_LAST_TICK = 1, COUNTER_SAMPLED = 2, COUNTER_SIGNAL = 3,
       COUNTER_TICK = 5 };

static const unsigned int tank_vr[] = {TANK_LEVEL, TANK_COUNT};
static const unsigned char tank_types[] = {SSX_FMI3_FLOAT64, SSX_FMI3_FLOAT64};
static const char *const tank_names[] = {"level", "count"};
static const unsigned int tank_clocks[] = {TANK_FULL};
static const ssx_fmi3_variables tank_variables = {
    .vr = tank_vr, .type = tank_types, .name = tank_names, .n = 2, .event_mode_used = 1,
    .early_return_allowed = 1, .output_clock_vr = tank_clocks, .n_output_clocks = 1};

static const unsigned int counter_vr[] = {COUNTER_COUNT, COUNTER_LAST_TICK, COUNTER_SAMPLED,
                                          COUNTER_SIGNAL};
static const unsigned char counter_types[] = {SSX_FMI3_FLOAT64, SSX_FMI3_FLOAT64,
                                              SSX_FMI3_FLOAT64, SSX_FMI3_FLOAT64};
static const char *const counter_names[] = {"count", "last_tick", "sampled", "signal"};
static const unsigned int counter_clocks[] = {COUNTER_TICK};
static const ssx_fmi3_variables counter_variables = {
    .vr = counter_vr, .type = counter_types, .name = counter_names, .n = 4,
    .event_mode_used = 1, .triggered_clock_vr = counter_clocks, .n_triggered_clocks = 1};

typedef struct {
    ssx_fmu *tank;
    ssx_fmu *counter;
    ssx_system *sys;
} tank_and_counter;

static tank_and_counter build(void)
{
    tank_and_counter s = {load_fmi3_fmu("level_detector_fmi3", &tank_variables, 0),
                          load_fmi3_fmu("tick_counter_fmi3", &counter_variables, 0),
                          ssx_system_new("tank and counter")};
    CHECK(start_fmu(s.tank, 0.0, 0.0, NULL, NULL, 0) == 0);
    CHECK(start_fmu(s.counter, 0.0, 0.0, NULL, NULL, 0) == 0);
    CHECK(ssx_add_fmu_component(s.sys, "Tank", s.tank, 1) == 0);
    CHECK(ssx_add_fmu_component(s.sys, "Counter", s.counter, 1) == 1);
    CHECK(ssx_add_output(s.sys, 0, SSX_REAL, TANK_LEVEL) == 0);
    CHECK(ssx_add_output(s.sys, 0, SSX_REAL, TANK_COUNT) == 1);
    CHECK(ssx_add_output(s.sys, 1, SSX_REAL, COUNTER_COUNT) == 0);
    CHECK(ssx_add_output(s.sys, 1, SSX_REAL, COUNTER_LAST_TICK) == 1);
    CHECK(ssx_add_output(s.sys, 1, SSX_REAL, COUNTER_SAMPLED) == 2);
    CHECK(ssx_add_input(s.sys, 1, SSX_REAL, COUNTER_SIGNAL, NAN) == 0);
    CHECK_OK(s.sys, ssx_connect(s.sys, 0, 0, 1, 0, 1.0, 0.0));
    return s;
}

static void release(tank_and_counter s)
{
    ssx_system_free(s.sys);
    ssx_fmu_free(s.tank);
    ssx_fmu_free(s.counter);
}

static void the_output_clock_ticks_the_connected_clock(void)
{
    tank_and_counter s = build();
    int source = ssx_add_output_clock_source(s.sys, 0, 0);
    CHECK(source == 0 && ssx_add_output_clock_source(s.sys, 0, 0) == 0);
    CHECK_OK(s.sys, ssx_connect_clock(s.sys, SSX_SOURCE_OUTPUT_CLOCK, source, 1, 0));
    CHECK_OK(s.sys, ssx_initialize(s.sys, 0.0));
    CHECK_OK(s.sys, ssx_run(s.sys, 0.0, 1.0, 0.25));
    /* each tank tick at 0.3 k, and the counter's at it: the system steps back and on to the
     * tick the tank returned early at (within the default tol_time, 1e-9) */
    const double full[] = {0.3, 0.6, 0.9};
    CHECK(ssx_event_count(s.sys) == 9);
    for (size_t k = 0; k < 3; ++k) {
        ssx_event_record event, clock, tick;
        CHECK(ssx_event_get(s.sys, 3 * k, &event) == 0);
        CHECK(ssx_event_get(s.sys, 3 * k + 1, &clock) == 0);
        CHECK(ssx_event_get(s.sys, 3 * k + 2, &tick) == 0);
        CHECK(event.own == SSX_OWN_FMU_EVENT && event.component == 0 && event.clock == 0);
        CHECK(clock.own == SSX_OWN_OUTPUT_CLOCK && clock.component == 0 && clock.clock == 1);
        CHECK(fabs(clock.t - full[k]) < 1e-12 && clock.t == event.t);
        CHECK(tick.own == SSX_OWN_CLOCK_TICK && tick.component == 1 && tick.clock == 1);
        CHECK(tick.t >= clock.t && tick.t - clock.t < 1e-9);
    }
    const double *counter = ssx_outputs(s.sys, 1);
    CHECK(counter[0] == 3.0 && fabs(counter[1] - 0.9) < 1e-9);
    CHECK(fabs(counter[2]) < 1e-9); /* the level the tick sampled: the emptied tank's */
    CHECK(ssx_outputs(s.sys, 0)[1] == 3.0);
    release(s);
}

static void connections_that_cannot_tick_are_refused(void)
{
    tank_and_counter s = build();
    CHECK(ssx_add_output_clock_source(s.sys, 0, 1) < 0);
    CHECK_MESSAGE(s.sys, "component 'Tank': unknown output clock 1 (it has 1)");
    CHECK(ssx_add_output_clock_source(s.sys, 1, 0) < 0);
    CHECK_MESSAGE(s.sys, "component 'Counter': unknown output clock 0 (it has 0)");
    CHECK(ssx_connect_clock(s.sys, SSX_SOURCE_OUTPUT_CLOCK, 0, 1, 0) < 0);
    CHECK_MESSAGE(s.sys, "unknown output clock source 0 (system 'tank and counter' has 0)");
    int source = ssx_add_output_clock_source(s.sys, 0, 0);
    CHECK(ssx_connect_clock(s.sys, SSX_SOURCE_OUTPUT_CLOCK, source, 0, 0) < 0);
    CHECK_MESSAGE(s.sys, "component 'Tank': unknown triggered input clock 0 (it has 0)");
    CHECK(ssx_connect_clock(s.sys, SSX_SOURCE_OWN_EVENTS, 0, 1, 0) < 0);
    CHECK_MESSAGE(s.sys, "a clock ticks on an indicator or an output clock, not on all of a "
                         "component's own events");
    CHECK(ssx_add_python_component(s.sys, "Py", 0) == 2);
    CHECK(ssx_connect_clock(s.sys, SSX_SOURCE_OUTPUT_CLOCK, source, 2, 0) < 0);
    CHECK_MESSAGE(s.sys, "component 'Py' is no FMI 3.0 Co-Simulation FMU: it has no triggered "
                         "input clocks");
    release(s);
}

/* models/Timer/timer.c: count, last_alarm; its clock follows the time */
enum { TIMER_COUNT = 0, TIMER_LAST_ALARM = 1, TIMER_ALARM = 7 };

static const unsigned int timer_vr[] = {TIMER_COUNT, TIMER_LAST_ALARM};
static const unsigned char timer_types[] = {SSX_FMI3_FLOAT64, SSX_FMI3_FLOAT64};
static const char *const timer_names[] = {"count", "last_alarm"};
static const unsigned int timer_clocks[] = {TIMER_ALARM};
static const ssx_fmi3_variables timer_variables = {
    .vr = timer_vr, .type = timer_types, .name = timer_names, .n = 2, .event_mode_used = 1,
    .countdown_clock_vr = timer_clocks, .n_countdown_clocks = 1};

static void a_restored_state_brings_back_the_planned_alarms(void)
{
    ssx_fmu *timer = load_fmi3_fmu("timer_fmi3", &timer_variables, 0);
    CHECK(start_fmu(timer, 0.0, 0.0, NULL, NULL, 0) == 0);
    ssx_system *sys = ssx_system_new("timer");
    CHECK(ssx_add_fmu_component(sys, "Timer", timer, 1) == 0);
    CHECK(ssx_add_output(sys, 0, SSX_REAL, TIMER_COUNT) == 0);
    CHECK(ssx_add_output(sys, 0, SSX_REAL, TIMER_LAST_ALARM) == 1);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.2, 0.2)); /* the alarm at 0.1 plans the next at 0.3 */
    CHECK(ssx_outputs(sys, 0)[0] == 1.0);
    ssx_system_state *at_02 = ssx_state_save(sys);
    CHECK(at_02 != NULL);
    for (int pass = 0; pass < 2; ++pass) { /* the second pass from the restored state */
        CHECK_OK(sys, ssx_run(sys, 0.2, 0.5, 0.3));
        const double *timer_outputs = ssx_outputs(sys, 0);
        CHECK(timer_outputs[0] == 2.0 && fabs(timer_outputs[1] - 0.3) < 1e-12);
        CHECK_OK(sys, ssx_state_restore(sys, at_02));
    }
    CHECK_OK(sys, ssx_run(sys, 0.2, 1.0, 0.8));
    CHECK(ssx_outputs(sys, 0)[0] == 3.0 && fabs(ssx_outputs(sys, 0)[1] - 0.7) < 1e-12);
    ssx_state_free(at_02);
    ssx_system_free(sys);
    ssx_fmu_free(timer);
}

int main(void)
{
    the_output_clock_ticks_the_connected_clock();
    connections_that_cannot_tick_are_refused();
    a_restored_state_brings_back_the_planned_alarms();
    return 0;
}
