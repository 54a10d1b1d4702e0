/* A bouncing ball written as hooks (the way a Python component reaches the engine): exact
 * free flight, snapshots in numbered slots, the bounce in handle_events. With exact flight the
 * only error left is the localization's, so the bounce times must match the closed form to the
 * time tolerance, for falling-only and for both-direction indicators. */
#include <math.h>

#include "test_support.h"

#define GRAVITY 9.81
#define RESTITUTION 0.7
#define TOL_TIME 1e-10

typedef struct {
    ssx_system *sys;
    int component;
    double h, v;
    double saved_h[2], saved_v[2];
    int bounces;
} ball;

static void publish(ball *b)
{
    double *out = ssx_outputs(b->sys, b->component);
    out[0] = b->h;
    out[1] = b->v;
}

static int fly(void *user, double t, double dt)
{
    (void)t;
    ball *b = user;
    b->h += b->v * dt - 0.5 * GRAVITY * dt * dt;
    b->v -= GRAVITY * dt;
    publish(b);
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
    ball *b = user;
    b->saved_h[slot] = b->h;
    b->saved_v[slot] = b->v;
    return 0;
}

static int load(void *user, int slot, double t)
{
    (void)t;
    ball *b = user;
    b->h = b->saved_h[slot];
    b->v = b->saved_v[slot];
    publish(b);
    return 0;
}

static int bounce(void *user, const int *indicators, int n, double t)
{
    (void)indicators;
    (void)n;
    (void)t;
    ball *b = user;
    b->v = -RESTITUTION * b->v;
    b->bounces++;
    publish(b);
    return 0;
}

/* Dropped from 1 m at rest: impacts at t1 = v1/g, then flights of 2 e^k v1 / g. */
static double bounce_time(int k)
{
    double v1 = sqrt(2.0 * GRAVITY);
    double t = v1 / GRAVITY;
    for (int j = 1; j < k; ++j) {
        t += 2.0 * pow(RESTITUTION, j) * v1 / GRAVITY;
    }
    return t;
}

static void run(int direction, ssx_locator locator)
{
    ssx_system *sys = ssx_system_new("hook ball");
    ball b = {.sys = sys, .h = 1.0, .v = 0.0};
    b.component = ssx_add_python_component(sys, "Ball", 1);
    CHECK(ssx_add_output(sys, b.component, SSX_REAL, 0) == 0);
    CHECK(ssx_add_output(sys, b.component, SSX_REAL, 1) == 1);
    ssx_hooks hooks = {.user = &b,
                       .do_step = fly,
                       .evaluate_outputs = show,
                       .snapshot = save,
                       .restore = load,
                       .handle_events = bounce};
    CHECK_OK(sys, ssx_set_hooks(sys, b.component, &hooks));
    CHECK(ssx_add_indicator_output(sys, b.component, 0, direction) == 0);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, b.component));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, TOL_TIME, 0.0, 100, 10, 0, locator, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));

    /* before the first impact every step costs one doStep and one snapshot */
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.4, 0.1));
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(stats.do_step_calls == 4 && stats.state_saves == 4 && stats.state_restores == 0);

    const int bounces = 8;
    CHECK_OK(sys, ssx_run(sys, 0.4, 0.5 * (bounce_time(bounces) + bounce_time(bounces + 1)), 0.1));
    CHECK(b.bounces == bounces);
    CHECK(ssx_event_count(sys) == (size_t)bounces);
    for (int k = 1; k <= bounces; ++k) {
        ssx_event_record event;
        CHECK(ssx_event_get(sys, (size_t)k - 1, &event) == 0);
        /* each located time is within TOL_TIME of the flight's impact; the impacts feed into
         * the next flight, so the bound grows with the bounce count */
        CHECK_CLOSE(event.t, bounce_time(k), 2.0 * TOL_TIME * k);
        CHECK(locator == SSX_BISECTION || event.iterations <= 10);
    }
    const double *values = ssx_history_values(sys, b.component);
    for (size_t k = 0; k < ssx_history_length(sys); ++k) {
        CHECK(values[2 * k] > -1e-8); /* never through the floor */
    }
    ssx_system_free(sys);
}

/* Default options past the accumulation point t_inf = t1 (1 + e) / (1 - e): the run ends with
 * a Zeno error, the ball never sinks through the floor, and the history stays readable. */
static void zeno_at_the_accumulation_point(void)
{
    ssx_system *sys = ssx_system_new("hook ball");
    ball b = {.sys = sys, .h = 1.0, .v = 0.0};
    b.component = ssx_add_python_component(sys, "Ball", 1);
    CHECK(ssx_add_output(sys, b.component, SSX_REAL, 0) == 0);
    CHECK(ssx_add_output(sys, b.component, SSX_REAL, 1) == 1);
    ssx_hooks hooks = {.user = &b, .do_step = fly, .evaluate_outputs = show, .snapshot = save,
                       .restore = load, .handle_events = bounce};
    CHECK_OK(sys, ssx_set_hooks(sys, b.component, &hooks));
    CHECK(ssx_add_indicator_output(sys, b.component, 0, -1) == 0);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, b.component));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    double t_inf = bounce_time(1) * (1.0 + RESTITUTION) / (1.0 - RESTITUTION);
    CHECK(ssx_run(sys, 0.0, t_inf + 1.0, 0.01) == -1);
    const ssx_error *e = ssx_last_error(sys);
    CHECK(e->kind == SSX_ERROR_ZENO && e->component == b.component && e->indicator == 0);
    CHECK(e->time < t_inf && e->time > t_inf - 1e-3);
    const double *values = ssx_history_values(sys, b.component);
    size_t n = ssx_history_length(sys);
    CHECK(ssx_history_time(sys)[n - 1] <= t_inf);
    for (size_t k = 0; k < n; ++k) {
        CHECK(values[2 * k] > -1e-8);
    }
    ssx_system_free(sys);
}

/* Thrown down from the floor itself: the indicator starts exactly on zero and goes to the far
 * side, which is a crossing at t0, handled once; then it bounces on flights of 2 e^k v0 / g. */
static void crossing_at_the_start_time(void)
{
    ssx_system *sys = ssx_system_new("hook ball");
    ball b = {.sys = sys, .h = 0.0, .v = -2.0};
    b.component = ssx_add_python_component(sys, "Ball", 1);
    CHECK(ssx_add_output(sys, b.component, SSX_REAL, 0) == 0);
    CHECK(ssx_add_output(sys, b.component, SSX_REAL, 1) == 1);
    ssx_hooks hooks = {.user = &b, .do_step = fly, .evaluate_outputs = show, .snapshot = save,
                       .restore = load, .handle_events = bounce};
    CHECK_OK(sys, ssx_set_hooks(sys, b.component, &hooks));
    CHECK(ssx_add_indicator_output(sys, b.component, 0, -1) == 0);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, b.component));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, TOL_TIME, 0.0, 100, 10, 0, SSX_ILLINOIS, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    double flight = 2.0 * RESTITUTION * 2.0 / GRAVITY;
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.5 * flight, 0.05));
    CHECK(ssx_event_count(sys) == 2);
    ssx_event_record first, second;
    CHECK(ssx_event_get(sys, 0, &first) == 0 && ssx_event_get(sys, 1, &second) == 0);
    CHECK(first.t == 0.0 && first.micro == 0);
    CHECK_CLOSE(second.t, flight, 2.0 * TOL_TIME);
    CHECK(ssx_history_time(sys)[1] == 0.0 && ssx_history_micro(sys)[1] == 1);
    ssx_system_free(sys);
}

int main(void)
{
    zeno_at_the_accumulation_point();
    crossing_at_the_start_time();
    run(-1, SSX_ILLINOIS);
    run(0, SSX_ILLINOIS);
    run(0, SSX_BISECTION);
    return 0;
}
