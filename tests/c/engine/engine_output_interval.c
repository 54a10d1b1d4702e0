/* Decimation (ssx_set_output_interval, ssx_set_run_output_interval): the history keeps every
 * k-th communication point, the end of each run and every event instant, with exactly the
 * values of the full history. */
#include <string.h>

#include "test_support.h"

/* seed_pendulum_system records theta, omega and alpha */
enum { INTERVAL = 10, PENDULUM_OUTPUTS = 3 };

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
    CHECK_OK(p->sys, ssx_initialize(p->sys, 0.0));
}

static void stop_bouncing(bouncing_pendulum *p)
{
    ssx_system_free(p->sys);
    ssx_fmu_free(p->fmu);
}

/* Row `row` of the full history equals row `kept` of the decimated one, bit for bit. */
static void check_same_row(ssx_system *full, size_t row, ssx_system *decimated, size_t kept)
{
    CHECK(ssx_history_time(full)[row] == ssx_history_time(decimated)[kept]);
    CHECK(ssx_history_micro(full)[row] == ssx_history_micro(decimated)[kept]);
    const size_t n = PENDULUM_OUTPUTS;
    CHECK(memcmp(ssx_history_values(full, 0) + row * n,
                 ssx_history_values(decimated, 0) + kept * n,
                 n * sizeof(double)) == 0);
}

/* Two runs 0 -> 0.55 -> 1.05 at dt 0.01: the grid count goes on across runs, each run's end
 * is kept, the event's two samples (before and after handling) are kept. */
static void check_hybrid_runs(void)
{
    const double dt = 0.01;
    bouncing_pendulum full;
    bouncing_pendulum decimated;
    start_bouncing(&full, 1);
    start_bouncing(&decimated, INTERVAL);
    const double ends[] = {0.55, 1.05};
    double t0 = 0.0;
    for (int r = 0; r < 2; ++r) {
        CHECK_OK(full.sys, ssx_run(full.sys, t0, ends[r], dt));
        CHECK_OK(decimated.sys, ssx_run(decimated.sys, t0, ends[r], dt));
        t0 = ends[r];
    }
    CHECK(full.bounce.calls == 1 && decimated.bounce.calls == 1);
    CHECK(ssx_event_count(decimated.sys) == 1);
    ssx_event_record event;
    CHECK(ssx_event_get(decimated.sys, 0, &event) == 0);

    /* grid points 0, 10, ..., 100, the ends 55 and 105, and the event before and after */
    CHECK(ssx_history_length(decimated.sys) == 11 + 2 + 2);
    size_t kept = 0;
    long grid_point = 0;
    int event_samples = 0;
    for (size_t row = 0; row < ssx_history_length(full.sys); ++row) {
        double t = ssx_history_time(full.sys)[row];
        if (t != event.t) {
            long k = grid_point++;
            if (k % INTERVAL != 0 && t != ends[0] && t != ends[1]) {
                continue;
            }
        } else {
            event_samples++;
        }
        check_same_row(full.sys, row, decimated.sys, kept++);
    }
    CHECK(event_samples == 2);
    CHECK(kept == ssx_history_length(decimated.sys));
    /* the reservation follows the decimation: the history never had room for every point */
    CHECK(ssx_history_bytes(decimated.sys) * 5 < ssx_history_bytes(full.sys));
    stop_bouncing(&full);
    stop_bouncing(&decimated);
}

/* The same runs with a run interval (ssx_set_run_output_interval) instead: each run counts
 * from its own start, so the second keeps 0.65, 0.75, ..., 1.05; a third run with 0 keeps
 * every point again. */
static void check_run_intervals(void)
{
    const double dt = 0.01;
    bouncing_pendulum full;
    bouncing_pendulum decimated;
    start_bouncing(&full, 1);
    start_bouncing(&decimated, 1);
    CHECK_OK(decimated.sys, ssx_set_run_output_interval(decimated.sys, INTERVAL));
    const double ends[] = {0.55, 1.05, 1.1};
    double t0 = 0.0;
    for (int r = 0; r < 3; ++r) {
        if (r == 2) {
            CHECK_OK(decimated.sys, ssx_set_run_output_interval(decimated.sys, 0));
        }
        CHECK_OK(full.sys, ssx_run(full.sys, t0, ends[r], dt));
        CHECK_OK(decimated.sys, ssx_run(decimated.sys, t0, ends[r], dt));
        t0 = ends[r];
    }
    ssx_event_record event;
    CHECK(ssx_event_get(decimated.sys, 0, &event) == 0);

    /* t0; 0.1 ... 0.5 and the end 0.55; 0.65 ... 1.05; 1.06 ... 1.1; the event twice */
    CHECK(ssx_history_length(decimated.sys) == 1 + 6 + 5 + 5 + 2);
    size_t kept = 0;
    int run = 0;
    long run_point = 1;
    for (size_t row = 1; row < ssx_history_length(full.sys); ++row) {
        double t = ssx_history_time(full.sys)[row];
        if (t != event.t) {
            long k = run_point++;
            int end = t == ends[run];
            int skipped = run < 2 && k % INTERVAL != 0 && !end;
            if (end) {
                run++;
                run_point = 1;
            }
            if (skipped) {
                continue;
            }
        }
        check_same_row(full.sys, row, decimated.sys, ++kept);
    }
    CHECK(kept + 1 == ssx_history_length(decimated.sys));
    stop_bouncing(&full);
    stop_bouncing(&decimated);
}

static void check_rejected_interval(void)
{
    ssx_system *sys = ssx_system_new("decimated");
    CHECK(ssx_set_output_interval(sys, 0) == -1);
    CHECK(strcmp(ssx_last_error(sys)->message, "system 'decimated': the output interval is a "
                                               "number of grid steps >= 1, not 0") == 0);
    CHECK(ssx_set_run_output_interval(sys, -1) == -1);
    CHECK(strcmp(ssx_last_error(sys)->message,
                 "system 'decimated': a run's output interval is a number of grid steps >= 1 "
                 "(or 0 for none), not -1") == 0);
    ssx_system_free(sys);
}

int main(void)
{
    check_hybrid_runs();
    check_run_intervals();
    check_rejected_interval();
    return 0;
}
