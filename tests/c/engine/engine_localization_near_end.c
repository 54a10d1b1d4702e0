/* Localization trials step on from the bracket's near end. On the seed's pendulum with theta's
 * declared derivative the first trial lands short of the crossing (the cubic Hermite's zero less
 * a margin), the second steps on from there across it: the first event costs one restore of
 * the macro step's start and one of the probe after the event, and its time stays within
 * tol_time of the crossing of the FMU's trajectory (bisection to 1e-13 as the reference).
 * A component whose trajectory depends on how it was stepped (a clock that runs late once it
 * has been stepped on from where it stood) can leave a final bracket whose far end, reached
 * from an earlier near end, does not cross on the trajectory through the last one: the system
 * then goes on from that end without an event, and the crossing is found after it, once, on
 * the fixed grid and under error-controlled steps alike. */
#include <math.h>

#include "test_support.h"

enum { PENDULUM_DER_THETA = 3 };

#define TOL_TIME 1e-9
#define REFERENCE_TOL_TIME 1e-13

static ssx_event_record first_event(ssx_fmu *fmu, ssx_locator locator, double tol_time,
                                    double tol_value, int slope, ssx_system **out)
{
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, locator, tol_time, tol_value, &c);
    if (slope) {
        CHECK_OK(sys, ssx_set_indicator_slope(sys, 0, PENDULUM_DER_THETA));
    }
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.05));
    CHECK(ssx_event_count(sys) == 1);
    ssx_event_record event;
    CHECK(ssx_event_get(sys, 0, &event) == 0);
    *out = sys;
    return event;
}

static void one_restore_before_the_trials(const char *stem)
{
    ssx_fmu *fmu = load_fmu(stem);
    ssx_system *sys;
    double crossing = first_event(fmu, SSX_BISECTION, REFERENCE_TOL_TIME, 0.0, 0, &sys).t;
    ssx_system_free(sys);
    ssx_event_record event = first_event(fmu, SSX_ILLINOIS, TOL_TIME, 1e-9, 1, &sys);
    CHECK(event.iterations == 2 && event.n_trials == 2);
    ssx_localization_trial short_of_it, across;
    CHECK(ssx_event_trial(sys, event.first_trial, &short_of_it) == 0 &&
          ssx_event_trial(sys, event.first_trial + 1, &across) == 0);
    printf("%s: first trial %.3g s before the crossing, second %.3g s after it; %d restores, "
           "%ld doSteps\n",
           stem, crossing - short_of_it.t, across.t - crossing, event.rollbacks, event.do_steps);
    /* the first trial is the near end the second steps on from */
    CHECK(short_of_it.t < crossing - REFERENCE_TOL_TIME && short_of_it.a == short_of_it.t);
    CHECK(across.a == short_of_it.t && across.b == across.t && across.t == event.t);
    CHECK(event.t >= crossing - REFERENCE_TOL_TIME && event.t - crossing <= TOL_TIME);
    /* the macro step's start before the first trial, the state at the event after the probe;
     * doSteps: the step that crossed, the two trials, the probe */
    CHECK(event.rollbacks == 2 && event.do_steps == 4);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* A clock x = t that, up to `until`, runs `late` behind once it has been stepped on from where
 * it stood (a doStep after a doStep since the macro piece began); its indicator T - x falls
 * through zero at T, or at T + late on such a trajectory. */
typedef struct {
    ssx_system *sys;
    int component;
    double t, crossing, late, until;
    int depth; /* doSteps since the macro piece's snapshot */
    double saved_t[2];
    int saved_depth[2];
    int handled;
} late_clock;

static void publish(late_clock *c)
{
    ssx_outputs(c->sys, c->component)[0] = c->crossing - c->t +
                                           (c->depth >= 2 && c->t <= c->until ? c->late : 0.0);
}

static int tick(void *user, double t, double dt)
{
    late_clock *c = user;
    c->t = t + dt;
    c->depth++;
    publish(c);
    return 0;
}

static int show(void *user, double t)
{
    (void)t;
    publish(user);
    return 0;
}

static int save(void *user, int slot)
{
    late_clock *c = user;
    if (slot == 0) {
        c->depth = 0;
    }
    c->saved_t[slot] = c->t;
    c->saved_depth[slot] = c->depth;
    return 0;
}

static int load(void *user, int slot, double t)
{
    (void)t;
    late_clock *c = user;
    c->t = c->saved_t[slot];
    c->depth = c->saved_depth[slot];
    publish(c);
    return 0;
}

static int count(void *user, const int *indicators, int n, double t)
{
    (void)indicators;
    (void)n;
    (void)t;
    ((late_clock *)user)->handled++;
    return 0;
}

/* adaptive: the same under error-controlled steps (which start at the grid step, and with no
 * input to judge stay there), whose pieces go on from where the last one reached */
static void no_crossing_through_the_last_near_end(int adaptive)
{
    /* bisection of [0.5, 0.6]: the first trial, 0.55, lands just past T (reached from the
     * macro step's start, on time); every later trial steps on from a near end and runs late,
     * so none crosses before 0.55 and the bracket closes on 0.55 from the near side */
    const double tol_time = 1e-10;
    const double late = 1e-6;
    ssx_system *sys = ssx_system_new("late clock");
    late_clock c = {.sys = sys, .crossing = 0.55 - 0.5 * late, .late = late,
                    .until = 0.55};
    c.component = ssx_add_python_component(sys, "Clock", 1);
    CHECK(ssx_add_output(sys, c.component, SSX_REAL, 0) == 0);
    ssx_hooks hooks = {.user = &c, .do_step = tick, .evaluate_outputs = show, .snapshot = save,
                       .restore = load, .handle_events = count};
    CHECK_OK(sys, ssx_set_hooks(sys, c.component, &hooks));
    CHECK(ssx_add_indicator_output(sys, c.component, 0, -1) == 0);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, c.component));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, tol_time, 0.0, 100, 5, 0, SSX_BISECTION, 0.0));
    if (adaptive) {
        ssx_step_control control = {.enabled = 1, .rtol = 1e-3, .atol = 1e-3, .min_step = 1e-6,
                                    .initial_step = 0.1, .safety = 0.9, .min_change = 0.2,
                                    .max_change = 5.0};
        CHECK_OK(sys, ssx_set_step_control(sys, &control));
    }
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.1));
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(ssx_event_count(sys) == 1 && stats.events == 1 && c.handled == 1);
    ssx_event_record event;
    CHECK(ssx_event_get(sys, 0, &event) == 0);
    printf("late clock%s: the event at 0.55 + %.3g s, after a bracket that closed on 0.55 "
           "without a crossing\n", adaptive ? " (adaptive steps)" : "", event.t - 0.55);
    /* found in the piece that starts at 0.55, where the clock runs on time again */
    CHECK(event.t > 0.55 && event.t - 0.55 <= tol_time);
    CHECK_CLOSE(event.t_left, 0.55, 1e-15);
    CHECK_CLOSE(event.t_right, 0.6, 1e-15);
    /* the samples' times never go back */
    const double *time = ssx_history_time(sys);
    for (size_t k = 1; k < ssx_history_length(sys); ++k) {
        CHECK(time[k] >= time[k - 1]);
    }
    ssx_system_free(sys);
}

int main(void)
{
    one_restore_before_the_trials("pendulum_euler");
    one_restore_before_the_trials("pendulum_cvode");
    no_crossing_through_the_last_near_end(0);
    no_crossing_through_the_last_near_end(1);
    return 0;
}
