/* Superdense time: handling one event makes another indicator cross at the same instant (a
 * cascade at micro step 1), and handlers that keep doing so end with the micro-step error. */
#include <math.h>
#include <string.h>

#include "test_support.h"

#define TOL_TIME 1e-10

/* A clock x = t with a discrete level y = +-1; outputs x - 0.5 and y. */
typedef struct {
    ssx_system *sys;
    int component;
    double t, level;
    double saved_t[2], saved_level[2];
    int toggle_on_level; /* the level's own event toggles it again: endless cascade */
    int handled[8];
    int n_handled;
} clock;

static void publish(clock *c)
{
    double *out = ssx_outputs(c->sys, c->component);
    out[0] = c->t - 0.5;
    out[1] = c->level;
}

static int tick(void *user, double t, double dt)
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
    c->saved_t[slot] = c->t;
    c->saved_level[slot] = c->level;
    return 0;
}

static int load(void *user, int slot, double t)
{
    (void)t;
    clock *c = user;
    c->t = c->saved_t[slot];
    c->level = c->saved_level[slot];
    publish(c);
    return 0;
}

static int handle(void *user, const int *indicators, int n, double t)
{
    (void)t;
    clock *c = user;
    for (int k = 0; k < n; ++k) {
        if (c->n_handled < 8) {
            c->handled[c->n_handled++] = indicators[k];
        }
        if (indicators[k] == 0 || c->toggle_on_level) {
            c->level = -c->level;
        }
    }
    publish(c);
    return 0;
}

static ssx_system *clock_system(clock *c, int level_direction, int toggle_on_level)
{
    ssx_system *sys = ssx_system_new("superdense");
    *c = (clock){.sys = sys, .level = 1.0, .toggle_on_level = toggle_on_level};
    c->component = ssx_add_python_component(sys, "Clock", 1);
    CHECK(ssx_add_output(sys, c->component, SSX_REAL, 0) == 0);
    CHECK(ssx_add_output(sys, c->component, SSX_REAL, 1) == 1);
    ssx_hooks hooks = {.user = c, .do_step = tick, .evaluate_outputs = show, .snapshot = save,
                       .restore = load, .handle_events = handle};
    CHECK_OK(sys, ssx_set_hooks(sys, c->component, &hooks));
    CHECK(ssx_add_indicator_output(sys, c->component, 0, 1) == 0);
    CHECK(ssx_add_indicator_output(sys, c->component, 1, level_direction) == 1);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, c->component));
    CHECK_OK(sys, ssx_add_event_connection(sys, 1, c->component));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, TOL_TIME, 0.0, 100, 5, 0, SSX_ILLINOIS, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    return sys;
}

static void one_cascade(void)
{
    clock c;
    ssx_system *sys = clock_system(&c, -1, 0);
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.1));
    CHECK(ssx_event_count(sys) == 2);
    ssx_event_record first, second;
    CHECK(ssx_event_get(sys, 0, &first) == 0 && ssx_event_get(sys, 1, &second) == 0);
    CHECK(first.indicator == 0 && first.micro == 0);
    CHECK(second.indicator == 1 && second.micro == 1 && second.t == first.t);
    CHECK(second.iterations == 0);
    CHECK(first.t >= 0.5 && first.t - 0.5 <= TOL_TIME); /* accepted on the far side */
    CHECK(c.n_handled == 2 && c.handled[0] == 0 && c.handled[1] == 1);
    /* the instant's samples: before, after round 0, after round 1 */
    const double *time = ssx_history_time(sys);
    const int *micro = ssx_history_micro(sys);
    const double *values = ssx_history_values(sys, c.component);
    size_t at = 0;
    while (time[at] != first.t) {
        ++at;
    }
    CHECK(micro[at] == 0 && micro[at + 1] == 1 && micro[at + 2] == 2);
    CHECK(time[at + 2] == first.t && time[at + 3] > first.t);
    CHECK(values[2 * at + 1] == 1.0 && values[2 * (at + 1) + 1] == -1.0);
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(stats.events == 2);
    ssx_system_free(sys);
}

static void endless_cascade(void)
{
    clock c;
    ssx_system *sys = clock_system(&c, 0, 1);
    CHECK(ssx_run(sys, 0.0, 1.0, 0.1) == -1);
    const ssx_error *e = ssx_last_error(sys);
    CHECK(e->kind == SSX_ERROR_ZENO && e->indicator == 1 && e->component == c.component);
    CHECK(strstr(e->message, "more than 5 micro steps") != NULL);
    CHECK(fabs(e->time - 0.5) <= TOL_TIME);
    ssx_system_free(sys);
}

int main(void)
{
    one_cascade();
    endless_cascade();
    return 0;
}
