/* The hybrid algorithm on the seed's pendulum (CVODE, rtol 1e-10): the event time against the
 * exact quarter period, the cost of event-free steps, Illinois against bisection, and a handler
 * that re-instantiates the FMU with the velocity reversed, like the seed tutorial. */
#include <math.h>

#include "test_support.h"

/* Quarter period for theta0 = 0.3 (scipy ellipk, same formula as PENDULUM_QUARTER_PERIOD). */
#define QUARTER_PERIOD_THETA0_03 0.4604085835449391

/* CVODE at rtol 1e-10 is good to ~1e-10 in theta; with |dtheta/dt| ~ 1 rad/s and tol_time 1e-9,
 * 1e-8 leaves a margin of ten over both. */
#define EVENT_TIME_TOLERANCE 1e-8

static void event_free_steps_cost_one_do_step(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, SSX_ILLINOIS, 1e-9, 1e-9, &c);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.45, 0.05)); /* theta stays positive up to 0.465 */
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(fmu, &counters);
    CHECK(stats.macro_steps == 9);
    CHECK(stats.do_step_calls == 9 && counters.do_step == 9);
    CHECK(stats.state_saves == 9 && counters.get_state == 9);
    CHECK(stats.state_restores == 0 && counters.set_state == 0);
    CHECK(ssx_event_count(sys) == 0);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static ssx_event_record locate_first_event(ssx_locator locator, double tol_value)
{
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, locator, 1e-9, tol_value, &c);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.05));

    /* without a handler the pendulum swings on: one falling crossing in [0, 1] */
    CHECK(ssx_event_count(sys) == 1);
    ssx_event_record event;
    CHECK(ssx_event_get(sys, 0, &event) == 0);
    CHECK_CLOSE(event.t, PENDULUM_QUARTER_PERIOD, EVENT_TIME_TOLERANCE);
    CHECK(event.micro == 0 && event.indicator == 0 && event.component == c);
    /* the accepted side: the indicator has crossed */
    size_t n = ssx_history_length(sys);
    const double *time = ssx_history_time(sys);
    const int *micro = ssx_history_micro(sys);
    const double *values = ssx_history_values(sys, c);
    CHECK(n == 21 + 2);
    size_t before = 0;
    while (before < n && !(time[before] == event.t && micro[before] == 0)) {
        ++before;
    }
    CHECK(before < n && micro[before + 1] == 1 && time[before + 1] == event.t);
    CHECK(values[before * 3] <= 0.0 && fabs(values[before * 3]) < 1e-8);
    for (size_t k = 1; k < n; ++k) {
        CHECK(time[k] >= time[k - 1]); /* no time skipped, none repeated except the event */
    }

    /* every doStep is accounted for: one per event-free piece, plus the event's own cost */
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(stats.events == 1);
    CHECK(stats.do_step_calls == (stats.macro_steps - 1) + event.do_steps);
    CHECK(stats.localization_iterations == event.iterations);
    CHECK(stats.state_restores == event.rollbacks);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
    return event;
}

/* record_internal_steps adds one sample per localization trial, marked with micro -1. */
static void internal_steps_recorded(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, SSX_ILLINOIS, 1e-9, 1e-9, &c);
    CHECK_OK(sys, ssx_set_hybrid_options(sys, 1e-9, 1e-9, 100, 10, 1, SSX_ILLINOIS, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.05));
    ssx_event_record event;
    CHECK(ssx_event_count(sys) == 1 && ssx_event_get(sys, 0, &event) == 0);
    size_t n = ssx_history_length(sys);
    CHECK(n == 21 + 2 + (size_t)event.iterations);
    const double *time = ssx_history_time(sys);
    const int *micro = ssx_history_micro(sys);
    int trials = 0;
    for (size_t k = 0; k < n; ++k) {
        if (micro[k] == -1) {
            CHECK(time[k] > 0.45 && time[k] < 0.5);
            ++trials;
        }
    }
    CHECK(trials == event.iterations);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static void handler_reverses_and_next_events_follow(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, SSX_ILLINOIS, 1e-9, 1e-9, &c);
    wall_bounce state = {.sys = sys, .fmu = fmu, .component = c};
    ssx_hooks hooks = {.user = &state, .handle_events = reverse_velocity};
    CHECK_OK(sys, ssx_set_hooks(sys, c, &hooks));
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, c));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 2.5, 0.05));

    /* reflected at theta = 0 the pendulum returns after half a period: events at (2k+1) t* */
    CHECK(ssx_event_count(sys) == 3);
    CHECK(state.calls == 3);
    for (size_t k = 0; k < 3; ++k) {
        ssx_event_record event;
        CHECK(ssx_event_get(sys, k, &event) == 0);
        CHECK_CLOSE(event.t, (2.0 * (double)k + 1.0) * PENDULUM_QUARTER_PERIOD,
                    EVENT_TIME_TOLERANCE * (double)(k + 1));
        CHECK(event.iterations <= 10);
    }
    /* before and after handling: same angle, reversed velocity */
    size_t n = ssx_history_length(sys);
    const int *micro = ssx_history_micro(sys);
    const double *values = ssx_history_values(sys, c);
    int pairs = 0;
    for (size_t k = 1; k < n; ++k) {
        if (micro[k] == 1) {
            CHECK(values[k * 3] == values[(k - 1) * 3]);
            CHECK(values[k * 3 + 1] == -values[(k - 1) * 3 + 1]);
            CHECK(values[k * 3 + 1] > 0.0);
            ++pairs;
        }
    }
    CHECK(pairs == 3);
    CHECK(n == 51 + 2 * 3);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* Two pendulums crossing within the same macro step: the earlier one is located first, each at
 * its own quarter period, and the whole-system rollback leaves both trajectories intact. */
static void two_crossings_in_one_step(void)
{
    ssx_fmu *wide = load_fmu("pendulum_cvode");
    ssx_fmu *narrow = load_fmu("pendulum_cvode");
    CHECK(start_pendulum(wide, 0.0, 0.5, 0.0, 1e-10) == 0);
    CHECK(start_pendulum(narrow, 0.0, 0.3, 0.0, 1e-10) == 0);
    ssx_system *sys = ssx_system_new("two pendulums");
    int a = add_pendulum(sys, "wide", wide);
    int b = add_pendulum(sys, "narrow", narrow);
    CHECK(ssx_add_indicator_output(sys, a, 0, -1) == 0);
    CHECK(ssx_add_indicator_output(sys, b, 0, -1) == 1);
    CHECK_OK(sys, ssx_set_hybrid_options(sys, 1e-9, 1e-9, 100, 10, 0, SSX_ILLINOIS, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.6, 0.05));
    CHECK(ssx_event_count(sys) == 2);
    ssx_event_record first, second;
    CHECK(ssx_event_get(sys, 0, &first) == 0 && ssx_event_get(sys, 1, &second) == 0);
    CHECK(first.indicator == 1 && first.component == b);
    CHECK(second.indicator == 0 && second.component == a);
    CHECK_CLOSE(first.t, QUARTER_PERIOD_THETA0_03, EVENT_TIME_TOLERANCE);
    CHECK_CLOSE(second.t, PENDULUM_QUARTER_PERIOD, EVENT_TIME_TOLERANCE);
    ssx_system_free(sys);
    ssx_fmu_free(wide);
    ssx_fmu_free(narrow);
}

int main(void)
{
    event_free_steps_cost_one_do_step();
    /* the seed's settings: tol_time = tol_value = 1e-9 */
    ssx_event_record seed_illinois = locate_first_event(SSX_ILLINOIS, 1e-9);
    ssx_event_record seed_bisection = locate_first_event(SSX_BISECTION, 1e-9);
    /* the bracket alone decides: halving 0.05 down to 1e-9 takes ceil(log2(5e7)) = 26 steps */
    ssx_event_record illinois = locate_first_event(SSX_ILLINOIS, 0.0);
    ssx_event_record bisection = locate_first_event(SSX_BISECTION, 0.0);
    printf("iterations with tol_value 1e-9: Illinois %d, bisection %d; with tol_value 0: "
           "Illinois %d, bisection %d\n",
           seed_illinois.iterations, seed_bisection.iterations, illinois.iterations,
           bisection.iterations);
    CHECK(seed_illinois.iterations <= 10);
    CHECK(illinois.iterations <= 10);
    CHECK(bisection.iterations == 26);
    internal_steps_recorded();
    handler_reverses_and_next_events_follow();
    two_crossings_in_one_step();
    return 0;
}
