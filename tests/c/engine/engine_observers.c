/* Observers added through the public API (ssx_add_observer) see exactly what the history keeps:
 * the same samples in the same order with the same values bit for bit, decimated alike, the
 * events and the restores of localization; with the history switched off they alone keep the
 * run; a removed observer is never called again; a failing callback stops the run. */
#include <math.h>
#include <string.h>

#include "test_support.h"

enum { PENDULUM_OUTPUTS = 3, MAX_SAMPLES = 4096 };

/* What one observer saw. */
typedef struct {
    ssx_system *sys;
    int component;
    int starts, restores, events, run_ends;
    size_t n;
    double t[MAX_SAMPLES];
    int micro[MAX_SAMPLES];
    double values[MAX_SAMPLES * PENDULUM_OUTPUTS];
    double last_restore;
    double event_time;
    int fail_at_sample; /* step_complete fails at this sample; -1: never */
} seen;

static int on_start(void *user, double t0)
{
    seen *s = user;
    (void)t0;
    s->starts++;
    return 0;
}

static int on_step_complete(void *user, double t, int micro)
{
    seen *s = user;
    if ((int)s->n == s->fail_at_sample) {
        return -1;
    }
    CHECK(s->n < MAX_SAMPLES);
    s->t[s->n] = t;
    s->micro[s->n] = micro;
    memcpy(&s->values[s->n * PENDULUM_OUTPUTS], ssx_outputs(s->sys, s->component),
           PENDULUM_OUTPUTS * sizeof(double));
    s->n++;
    return 0;
}

static int on_state_restored(void *user, double t)
{
    seen *s = user;
    s->restores++;
    s->last_restore = t;
    return 0;
}

static int on_event(void *user, const ssx_event_record *record)
{
    seen *s = user;
    s->events++;
    s->event_time = record->t;
    return 0;
}

static int on_run_end(void *user)
{
    ((seen *)user)->run_ends++;
    return 0;
}

static const ssx_observer_callbacks CALLBACKS = {on_start, on_step_complete, on_state_restored,
                                                 on_event, on_run_end};

typedef struct {
    ssx_system *sys;
    ssx_fmu *fmu;
    wall_bounce bounce;
} bouncing_pendulum;

/* The seed's pendulum against the wall at theta = 0: one event near 0.465 s within 1 s. */
static void start_bouncing(bouncing_pendulum *p, int output_interval)
{
    int c;
    p->fmu = load_fmu("pendulum_cvode");
    p->sys = seed_pendulum_system(p->fmu, SSX_ILLINOIS, 1e-9, 0.0, &c);
    p->bounce = (wall_bounce){.sys = p->sys, .fmu = p->fmu, .component = c};
    ssx_hooks hooks = {.user = &p->bounce, .handle_events = reverse_velocity};
    CHECK_OK(p->sys, ssx_set_hooks(p->sys, c, &hooks));
    CHECK_OK(p->sys, ssx_add_event_connection(p->sys, 0, c));
    CHECK_OK(p->sys, ssx_set_output_interval(p->sys, output_interval));
}

static void stop_bouncing(bouncing_pendulum *p)
{
    ssx_system_free(p->sys);
    ssx_fmu_free(p->fmu);
}

/* The observer saw the history's samples, bit for bit. */
static void check_same_as_history(ssx_system *sys, const seen *s)
{
    size_t n = ssx_history_length(sys);
    CHECK(n > 0 && s->n == n);
    CHECK(memcmp(s->t, ssx_history_time(sys), n * sizeof(double)) == 0);
    CHECK(memcmp(s->micro, ssx_history_micro(sys), n * sizeof(int)) == 0);
    CHECK(memcmp(s->values, ssx_history_values(sys, 0), n * PENDULUM_OUTPUTS * sizeof(double)) ==
          0);
}

/* Two runs with an event between them, every sample kept, and every 7th. */
static void check_equal_to_history(int output_interval)
{
    bouncing_pendulum p;
    start_bouncing(&p, output_interval);
    static seen s;
    s = (seen){.sys = p.sys, .component = 0, .fail_at_sample = -1};
    CHECK(ssx_add_observer(p.sys, &CALLBACKS, &s) > 0);
    CHECK_OK(p.sys, ssx_initialize(p.sys, 0.0));
    CHECK_OK(p.sys, ssx_run(p.sys, 0.0, 0.55, 0.01));
    CHECK_OK(p.sys, ssx_run(p.sys, 0.55, 1.0, 0.01));
    CHECK(s.starts == 1 && s.run_ends == 2);
    CHECK(s.events == 1 && ssx_event_count(p.sys) == 1);
    ssx_event_record event;
    CHECK(ssx_event_get(p.sys, 0, &event) == 0 && s.event_time == event.t);
    CHECK_CLOSE(event.t, PENDULUM_QUARTER_PERIOD, 1e-6);
    /* localization went back to the start of the event's step, at least once per trial */
    ssx_statistics stats;
    ssx_get_statistics(p.sys, &stats);
    CHECK(s.restores >= 1 && s.restores == (int)stats.state_restores);
    check_same_as_history(p.sys, &s);
    stop_bouncing(&p);
}

/* ssx_set_history(0): the history keeps nothing, the observer everything it kept before. */
static void check_history_off(void)
{
    bouncing_pendulum kept;
    bouncing_pendulum unkept;
    start_bouncing(&kept, 1);
    start_bouncing(&unkept, 1);
    static seen a, b;
    a = (seen){.sys = kept.sys, .fail_at_sample = -1};
    b = (seen){.sys = unkept.sys, .fail_at_sample = -1};
    CHECK(ssx_add_observer(kept.sys, &CALLBACKS, &a) > 0);
    CHECK(ssx_add_observer(unkept.sys, &CALLBACKS, &b) > 0);
    CHECK_OK(unkept.sys, ssx_set_history(unkept.sys, 0));
    CHECK_OK(kept.sys, ssx_initialize(kept.sys, 0.0));
    CHECK_OK(unkept.sys, ssx_initialize(unkept.sys, 0.0));
    CHECK_OK(kept.sys, ssx_run(kept.sys, 0.0, 1.0, 0.01));
    CHECK_OK(unkept.sys, ssx_run(unkept.sys, 0.0, 1.0, 0.01));
    CHECK(ssx_history_length(unkept.sys) == 0);
    check_same_as_history(kept.sys, &b);
    /* and back on: the next initialization keeps the history again */
    CHECK_OK(unkept.sys, ssx_set_history(unkept.sys, 1));
    CHECK_OK(unkept.sys, ssx_initialize(unkept.sys, 1.0));
    CHECK_OK(unkept.sys, ssx_run(unkept.sys, 1.0, 1.2, 0.01));
    CHECK(ssx_history_length(unkept.sys) == 21);
    stop_bouncing(&kept);
    stop_bouncing(&unkept);
}

/* Added after ssx_initialize, an observer starts with the next run; removed, it is never
 * called again; an unknown id is refused. */
static void check_add_and_remove(void)
{
    bouncing_pendulum p;
    start_bouncing(&p, 1);
    CHECK_OK(p.sys, ssx_initialize(p.sys, 0.0));
    static seen s;
    s = (seen){.sys = p.sys, .fail_at_sample = -1};
    int id = ssx_add_observer(p.sys, &CALLBACKS, &s);
    CHECK(id > 0);
    CHECK_OK(p.sys, ssx_run(p.sys, 0.0, 0.1, 0.01));
    CHECK(s.starts == 1 && s.n == 10); /* t0 was recorded before it came */
    CHECK(s.t[0] == ssx_history_time(p.sys)[1]);
    CHECK_OK(p.sys, ssx_remove_observer(p.sys, id));
    CHECK_OK(p.sys, ssx_run(p.sys, 0.1, 0.2, 0.01));
    CHECK(s.n == 10 && s.run_ends == 1);
    CHECK(ssx_remove_observer(p.sys, id) != 0);
    CHECK_MESSAGE(p.sys, "no observer");
    CHECK(ssx_add_observer(p.sys, NULL, NULL) < 0);
    stop_bouncing(&p);
}

/* A callback that fails stops the run: kind SSX_ERROR_CALLBACK at the sample's time, and the
 * samples before it stay in the history. */
static void check_failing_observer(void)
{
    bouncing_pendulum p;
    start_bouncing(&p, 1);
    static seen s;
    s = (seen){.sys = p.sys, .fail_at_sample = 5};
    CHECK(ssx_add_observer(p.sys, &CALLBACKS, &s) > 0);
    CHECK_OK(p.sys, ssx_initialize(p.sys, 0.0));
    CHECK(ssx_run(p.sys, 0.0, 1.0, 0.01) != 0);
    const ssx_error *error = ssx_last_error(p.sys);
    CHECK(error->kind == SSX_ERROR_CALLBACK);
    CHECK_MESSAGE(p.sys, "step_complete callback failed");
    CHECK(error->time == 0.05);
    CHECK(ssx_history_length(p.sys) == 6); /* the history comes first: t = 0 ... 0.05 */
    stop_bouncing(&p);
}

/* What a block observer was handed, gathered. */
typedef struct {
    size_t n, blocks, columns;
    double t[MAX_SAMPLES];
    int micro[MAX_SAMPLES];
    double values[MAX_SAMPLES * PENDULUM_OUTPUTS];
} gathered;

static int gather(void *user, const double *t, const int *micro, const double *values,
                  size_t n_rows, size_t n_columns)
{
    gathered *g = user;
    CHECK(g->n + n_rows <= MAX_SAMPLES && n_columns == PENDULUM_OUTPUTS);
    memcpy(g->t + g->n, t, n_rows * sizeof *t);
    memcpy(g->micro + g->n, micro, n_rows * sizeof *micro);
    memcpy(g->values + g->n * n_columns, values, n_rows * n_columns * sizeof *values);
    g->n += n_rows;
    g->blocks++;
    g->columns = n_columns;
    return 0;
}

/* Blocks of 16 rows: together, the history bit for bit; the end of ssx_initialize and of
 * each run closes a block. */
static void check_blocks(void)
{
    bouncing_pendulum p;
    start_bouncing(&p, 1);
    static gathered g;
    g = (gathered){0};
    CHECK(ssx_add_block_observer(p.sys, 16, gather, &g) > 0);
    CHECK(ssx_add_block_observer(p.sys, 0, gather, &g) < 0);
    CHECK_OK(p.sys, ssx_initialize(p.sys, 0.0));
    CHECK_OK(p.sys, ssx_run(p.sys, 0.0, 0.55, 0.01));
    size_t first_run = ssx_history_length(p.sys);
    CHECK(g.n == first_run); /* nothing waits for the next run */
    CHECK_OK(p.sys, ssx_run(p.sys, 0.55, 1.0, 0.01));
    size_t n = ssx_history_length(p.sys);
    /* the sample at t0 closes a block of its own (it ends ssx_initialize) */
    CHECK(g.n == n && g.blocks == 1 + (first_run - 1 + 15) / 16 + (n - first_run + 15) / 16);
    CHECK(memcmp(g.t, ssx_history_time(p.sys), n * sizeof(double)) == 0);
    CHECK(memcmp(g.micro, ssx_history_micro(p.sys), n * sizeof(int)) == 0);
    CHECK(memcmp(g.values, ssx_history_values(p.sys, 0), n * PENDULUM_OUTPUTS * sizeof(double)) ==
          0);
    stop_bouncing(&p);
}

/* A writer that stops the run at its third block: answering -1 it has not written the block,
 * which is handed again as the run ends; answering 1 it has, and it is not handed again.
 * Either way what was gathered is the history, each sample once. */
typedef struct {
    gathered g;
    int calls, answer;
} stopping_writer;

static int stop_at_third_block(void *user, const double *t, const int *micro,
                               const double *values, size_t n_rows, size_t n_columns)
{
    stopping_writer *w = user;
    if (++w->calls == 3 && w->answer < 0) {
        return w->answer;
    }
    gather(&w->g, t, micro, values, n_rows, n_columns);
    return w->calls == 3 ? w->answer : 0;
}

static void check_block_writer_stopping_the_run(int answer)
{
    bouncing_pendulum p;
    start_bouncing(&p, 1);
    static stopping_writer w;
    w = (stopping_writer){.answer = answer};
    CHECK(ssx_add_block_observer(p.sys, 16, stop_at_third_block, &w) > 0);
    CHECK_OK(p.sys, ssx_initialize(p.sys, 0.0));
    CHECK(ssx_run(p.sys, 0.0, 1.0, 0.01) != 0);
    CHECK(ssx_last_error(p.sys)->kind == SSX_ERROR_CALLBACK);
    size_t n = ssx_history_length(p.sys);
    CHECK(n == 1 + 2 * 16 && w.g.n == n);
    CHECK(memcmp(w.g.t, ssx_history_time(p.sys), n * sizeof(double)) == 0);
    CHECK(memcmp(w.g.values, ssx_history_values(p.sys, 0), n * PENDULUM_OUTPUTS * sizeof(double)) ==
          0);
    stop_bouncing(&p);
}

int main(void)
{
    check_blocks();
    check_block_writer_stopping_the_run(-1);
    check_block_writer_stopping_the_run(1);
    check_equal_to_history(1);
    check_equal_to_history(7);
    check_history_off();
    check_add_and_remove();
    check_failing_observer();
    puts("observers: ok");
    return 0;
}
