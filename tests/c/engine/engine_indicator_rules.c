/* Indicators written as hooks of a component that only keeps time, so every crossing is known
 * exactly: an indicator that reaches zero and rests there crosses once (in the direction it
 * arrived from), and on a piecewise-constant indicator the default localization needs at most
 * two iterations more than bisection. */
#include <math.h>

#include "test_support.h"

#define TOL_TIME 1e-9
#define REST_START 0.35
#define HOLD_STEP 1e-3

typedef struct {
    ssx_system *sys;
    int component;
    double (*shape)(double t);
    double t;
    double saved[2];
    int handled;
} clock;

static double resting_after_fall(double t)
{
    return t < REST_START ? REST_START - t : 0.0;
}

/* (0.3005 - t)^3 held every HOLD_STEP: jumps below zero at the sample instant 0.301. Flat
 * between samples and curved across them, it makes regula falsi creep. */
static double held_cubic(double t)
{
    double d = 0.3005 - floor(t / HOLD_STEP) * HOLD_STEP;
    return d * d * d;
}

static void publish(clock *c)
{
    ssx_outputs(c->sys, c->component)[0] = c->shape(c->t);
}

static int advance(void *user, double t, double dt)
{
    clock *c = user;
    c->t = t + dt;
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
    clock *c = user;
    c->saved[slot] = c->t;
    return 0;
}

static int load(void *user, int slot, double t)
{
    (void)t;
    clock *c = user;
    c->t = c->saved[slot];
    publish(c);
    return 0;
}

static int count(void *user, const int *indicators, int n, double t)
{
    (void)indicators;
    (void)n;
    (void)t;
    ((clock *)user)->handled++;
    return 0;
}

static ssx_system *clock_system(clock *c, double (*shape)(double), int direction,
                                ssx_locator locator)
{
    ssx_system *sys = ssx_system_new("clock");
    *c = (clock){.sys = sys, .shape = shape};
    c->component = ssx_add_python_component(sys, "C", 1);
    CHECK(ssx_add_output(sys, c->component, SSX_REAL, 0) == 0);
    ssx_hooks hooks = {.user = c, .do_step = advance, .evaluate_outputs = show,
                       .snapshot = save, .restore = load, .handle_events = count};
    CHECK_OK(sys, ssx_set_hooks(sys, c->component, &hooks));
    CHECK(ssx_add_indicator_output(sys, c->component, 0, direction) == 0);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, c->component));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, TOL_TIME, 0.0, 100, 10, 0, locator, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    return sys;
}

/* Falls onto zero at 0.35 and rests there for the remaining 65 macro steps. */
static void rest_on_zero(int direction, int events)
{
    clock c;
    ssx_system *sys = clock_system(&c, resting_after_fall, direction, SSX_ILLINOIS);
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.01));
    CHECK(ssx_event_count(sys) == (size_t)events && c.handled == events);
    if (events == 1) {
        ssx_event_record event;
        CHECK(ssx_event_get(sys, 0, &event) == 0);
        CHECK(event.t >= REST_START && event.t <= REST_START + TOL_TIME + 1e-12);
    }
    ssx_system_free(sys);
}

static int iterations_on_held_cubic(ssx_locator locator)
{
    clock c;
    ssx_system *sys = clock_system(&c, held_cubic, -1, locator);
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.5, 0.05));
    CHECK(ssx_event_count(sys) == 1);
    ssx_event_record event;
    CHECK(ssx_event_get(sys, 0, &event) == 0);
    /* the far side of the jump at the sample instant 0.301 */
    CHECK(event.t >= 0.301 - 1e-12 && event.t <= 0.301 + TOL_TIME);
    ssx_system_free(sys);
    return event.iterations;
}

int main(void)
{
    rest_on_zero(-1, 1);
    rest_on_zero(1, 0);
    rest_on_zero(0, 1);
    int bisection = iterations_on_held_cubic(SSX_BISECTION);
    CHECK(bisection == 26); /* 0.05 halved down to 1e-9 */
    CHECK(iterations_on_held_cubic(SSX_ILLINOIS) <= bisection + 2);
    CHECK(iterations_on_held_cubic(SSX_ILLINOIS_UNGUARDED) > bisection + 2);
    return 0;
}
