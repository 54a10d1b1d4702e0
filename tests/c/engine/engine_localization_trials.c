/* The localization trials kept with the event records, on the seed's pendulum (CVODE, rtol
 * 1e-10, falling crossing of theta in [0.45, 0.5]): one trial per iteration, brackets nested and
 * shrinking around the event, the indicator's sign telling the side of each trial, and nothing
 * recorded without events. */
#include <math.h>

#include "test_support.h"

#define TOL_TIME 1e-9

/* theta as recorded on the grid at t (the indicator is output 0) */
static double recorded_theta(const ssx_system *sys, int component, double t)
{
    const double *time = ssx_history_time(sys);
    const int *micro = ssx_history_micro(sys);
    for (size_t k = 0; k < ssx_history_length(sys); ++k) {
        if (time[k] == t && micro[k] == 0) {
            return ssx_history_values(sys, component)[k * 3];
        }
    }
    CHECK(!"no sample at t");
    return NAN;
}

static void trials_of_the_first_event(ssx_locator locator, double tol_value)
{
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, locator, TOL_TIME, tol_value, &c);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.05));
    ssx_event_record event;
    CHECK(ssx_event_count(sys) == 1 && ssx_event_get(sys, 0, &event) == 0);

    /* the initial bracket is the macro step that crossed; its ends are the grid samples */
    CHECK(event.t_left == 0.45 && event.t_right == 0.5);
    CHECK(event.value_left == recorded_theta(sys, c, 0.45) && event.value_left > 0.0);
    CHECK(event.value_right < 0.0);

    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(event.n_trials == event.iterations && event.n_trials > 0);
    CHECK(stats.localization_iterations == event.n_trials);
    CHECK(event.first_trial == 0 && ssx_event_trial_count(sys) == (size_t)event.n_trials);
    CHECK(ssx_event_trial(sys, (size_t)event.n_trials, &(ssx_localization_trial){0}) == -1);

    double a = event.t_left, b = event.t_right, value_at_b = event.value_right;
    for (int k = 0; k < event.n_trials; ++k) {
        ssx_localization_trial trial;
        CHECK(ssx_event_trial(sys, event.first_trial + (size_t)k, &trial) == 0);
        CHECK(trial.t > a && trial.t < b);
        /* nested and shrinking: the trial becomes the end on its side */
        CHECK(trial.a >= a && trial.b <= b && trial.b - trial.a < b - a);
        if (trial.value <= 0.0) {
            CHECK(trial.b == trial.t && trial.a == a);
            value_at_b = trial.value;
        } else {
            CHECK(trial.a == trial.t && trial.b == b);
        }
        if (locator == SSX_BISECTION) {
            /* the midpoint: each bracket is half the one before, up to rounding */
            CHECK_CLOSE(trial.b - trial.a, 0.5 * (b - a), 1e-15);
        }
        a = trial.a;
        b = trial.b;
    }
    /* the located time is the far end of the last bracket, reached within a tolerance */
    CHECK(b == event.t);
    CHECK(b - a <= TOL_TIME || fabs(value_at_b) <= tol_value);
    if (tol_value == 0.0) {
        CHECK(b - a <= TOL_TIME);
    }
    printf("%s, tol_value %g: %d trials, last bracket width %.3g, indicator at t %.3g\n",
           locator == SSX_ILLINOIS ? "Illinois" : "bisection", tol_value, event.n_trials, b - a,
           value_at_b);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static void no_event_no_trials(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, SSX_ILLINOIS, TOL_TIME, 1e-9, &c);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.45, 0.05));
    CHECK(ssx_event_count(sys) == 0 && ssx_event_trial_count(sys) == 0);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* Reflected at every crossing, the pendulum has three events in [0, 2.5]: each record lists its
 * own trials, one after the other in the shared buffer. */
static void trials_of_successive_events(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, SSX_BISECTION, TOL_TIME, 1e-9, &c);
    wall_bounce state = {.sys = sys, .fmu = fmu, .component = c};
    ssx_hooks hooks = {.user = &state, .handle_events = reverse_velocity};
    CHECK_OK(sys, ssx_set_hooks(sys, c, &hooks));
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, c));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 2.5, 0.05));
    CHECK(ssx_event_count(sys) == 3);
    size_t next = 0;
    for (size_t k = 0; k < 3; ++k) {
        ssx_event_record event;
        CHECK(ssx_event_get(sys, k, &event) == 0);
        CHECK(event.first_trial == next && event.n_trials == event.iterations);
        next += (size_t)event.n_trials;
        ssx_localization_trial last;
        CHECK(ssx_event_trial(sys, next - 1, &last) == 0);
        CHECK(last.a < event.t && last.b == event.t);
        CHECK(event.t_left <= last.a && event.t_right >= last.b);
    }
    CHECK(ssx_event_trial_count(sys) == next);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    trials_of_the_first_event(SSX_ILLINOIS, 1e-9);
    trials_of_the_first_event(SSX_BISECTION, 1e-9);
    trials_of_the_first_event(SSX_ILLINOIS, 0.0);
    trials_of_the_first_event(SSX_BISECTION, 0.0);
    no_event_no_trials();
    trials_of_successive_events();
    return 0;
}
