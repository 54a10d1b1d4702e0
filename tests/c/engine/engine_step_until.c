/* The execution taken a stretch at a time (ssx_step_until): the seed's pendulum against a
 * wall, its wall restarting it declaratively (ssx_set_restart_handler), stepped at an
 * importer's communication points. It stops right after each wall hit, at the exact time; a
 * run made of such stretches is the run ssx_run makes, sample for sample; a stop off the grid
 * ends the step that would cross it and the next call completes that step. */
#include <math.h>

#include "test_support.h"

#define STOP_TIME 2.5
#define GRID_STEP 0.05

/* The seed's pendulum (theta0 = 0.5, CVODE rtol 1e-10) against a wall at theta = 0: the
 * restart handler starts it again with its velocity reversed. */
static ssx_system *wall_system(ssx_fmu **fmu)
{
    *fmu = load_fmu("pendulum_cvode");
    int pendulum;
    ssx_system *sys = seed_pendulum_system(*fmu, SSX_ILLINOIS, 1e-9, 1e-9, &pendulum);
    add_wall_restart(sys, pendulum);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    return sys;
}

static void free_wall_system(ssx_system *sys, ssx_fmu *fmu)
{
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* Both systems recorded the same samples and events, bit for bit. */
static void check_same_history(const ssx_system *a, const ssx_system *b)
{
    size_t n = ssx_history_length(a);
    CHECK(n > 0 && ssx_history_length(b) == n);
    CHECK(memcmp(ssx_history_time(a), ssx_history_time(b), n * sizeof(double)) == 0);
    CHECK(memcmp(ssx_history_micro(a), ssx_history_micro(b), n * sizeof(int)) == 0);
    CHECK(memcmp(ssx_history_values(a, 0), ssx_history_values(b, 0), 3 * n * sizeof(double)) ==
          0);
    CHECK(ssx_event_count(a) == ssx_event_count(b));
    for (size_t k = 0; k < ssx_event_count(a); ++k) {
        ssx_event_record ea, eb;
        CHECK(ssx_event_get(a, k, &ea) == 0 && ssx_event_get(b, k, &eb) == 0);
        CHECK(ea.t == eb.t && ea.micro == eb.micro && ea.iterations == eb.iterations);
    }
}

/* At the importer's points k * 0.05 the call returns right after the first wall hit, at the
 * quarter period; the hits go on at odd multiples of it. */
static void stops_right_after_the_wall_hit(void)
{
    ssx_fmu *fmu;
    ssx_system *sys = wall_system(&fmu);
    ssx_step_outcome out;
    int k = 1;
    for (;; ++k) {
        CHECK_OK(sys, ssx_step_until(sys, k * GRID_STEP, GRID_STEP, &out));
        CHECK(out.status == 0 && !out.terminated);
        if (out.event) {
            break;
        }
        CHECK(out.time == k * GRID_STEP && out.events == 0);
    }
    CHECK(k == 10); /* the hit lies in (0.45, 0.5] */
    CHECK_CLOSE(out.time, PENDULUM_QUARTER_PERIOD, 1e-9);
    CHECK(out.events == 1 && ssx_time(sys) == out.time);
    ssx_event_record hit;
    CHECK(ssx_event_count(sys) == 1 && ssx_event_get(sys, 0, &hit) == 0 && hit.t == out.time);
    /* the sample after handling is the last one: nothing was stepped past the hit */
    size_t n = ssx_history_length(sys);
    CHECK(ssx_history_time(sys)[n - 1] == out.time && ssx_history_micro(sys)[n - 1] == 1);
    /* the same call again completes the stretch to 0.5 */
    CHECK_OK(sys, ssx_step_until(sys, k * GRID_STEP, GRID_STEP, &out));
    CHECK(!out.event && out.time == k * GRID_STEP && out.events == 1);
    for (++k; k * GRID_STEP <= STOP_TIME + 1e-12; ++k) {
        do {
            CHECK_OK(sys, ssx_step_until(sys, k * GRID_STEP, GRID_STEP, &out));
        } while (out.event);
    }
    CHECK(ssx_event_count(sys) == 3);
    for (size_t e = 0; e < 3; ++e) {
        CHECK(ssx_event_get(sys, e, &hit) == 0);
        CHECK_CLOSE(hit.t, (2.0 * (double)e + 1.0) * PENDULUM_QUARTER_PERIOD, 1e-8);
    }
    free_wall_system(sys, fmu);
}

/* ssx_run and a loop of ssx_step_until to the same end record the same run, and so do
 * stretches whose ends lie on the grid. */
static void stretches_make_the_run(void)
{
    ssx_fmu *fmu_run, *fmu_loop, *fmu_grid;
    ssx_system *run = wall_system(&fmu_run);
    ssx_system *loop = wall_system(&fmu_loop);
    ssx_system *grid = wall_system(&fmu_grid);
    CHECK_OK(run, ssx_run(run, 0.0, STOP_TIME, GRID_STEP));
    ssx_step_outcome out;
    int stops = 0;
    do {
        CHECK_OK(loop, ssx_step_until(loop, STOP_TIME, GRID_STEP, &out));
        stops += out.event;
    } while (out.time < STOP_TIME);
    CHECK(stops == 3 && out.events == 3 && !out.event);
    for (int k = 1; k <= 10; ++k) {
        do {
            CHECK_OK(grid, ssx_step_until(grid, (5 * k) * GRID_STEP, GRID_STEP, &out));
        } while (out.event);
    }
    check_same_history(run, loop);
    check_same_history(run, grid);
    ssx_statistics a, b;
    ssx_get_statistics(run, &a);
    ssx_get_statistics(loop, &b);
    CHECK(a.macro_steps == b.macro_steps && a.do_step_calls == b.do_step_calls &&
          a.state_restores == b.state_restores);
    free_wall_system(run, fmu_run);
    free_wall_system(loop, fmu_loop);
    free_wall_system(grid, fmu_grid);
}

/* A stop at 0.07 on the grid of 0.05 ends the step (0.05, 0.1) there; the next call goes on
 * to 0.1 and then 0.14, keeping the grid. */
static void a_stop_off_the_grid_cuts_one_step(void)
{
    ssx_fmu *fmu;
    ssx_system *sys = wall_system(&fmu);
    ssx_step_outcome out;
    CHECK_OK(sys, ssx_step_until(sys, 0.07, GRID_STEP, &out));
    CHECK(out.time == 0.07 && !out.event);
    CHECK_OK(sys, ssx_step_until(sys, 0.14, GRID_STEP, &out));
    CHECK(out.time == 0.14);
    const double expected[] = {0.0, 0.05, 0.07, 0.1, 0.14};
    CHECK(ssx_history_length(sys) == 5);
    CHECK(memcmp(ssx_history_time(sys), expected, sizeof expected) == 0);
    /* 0.15, then the step to 0.2 ends 1e-13 early: a remainder below 1e-9 steps joins the
     * next step instead of making a sliver one */
    CHECK_OK(sys, ssx_step_until(sys, 0.2 - 1e-13, GRID_STEP, &out));
    CHECK_OK(sys, ssx_step_until(sys, 0.25, GRID_STEP, &out));
    CHECK(ssx_history_length(sys) == 8 && ssx_history_time(sys)[5] == 3 * GRID_STEP);
    CHECK(ssx_history_time(sys)[6] == 0.2 - 1e-13 && ssx_history_time(sys)[7] == 0.25);
    /* refused: going back, a non-positive step */
    CHECK(ssx_step_until(sys, 0.1, GRID_STEP, &out) == -1 && out.status == -1);
    CHECK_MESSAGE(sys, "past t_stop");
    CHECK(ssx_step_until(sys, 0.3, 0.0, &out) == -1);
    CHECK_MESSAGE(sys, "must be positive");
    free_wall_system(sys, fmu);
}

/* models/BouncingBall/bouncing_ball.c */
enum { BALL_H = 0, BALL_V = 1, BALL_E = 5, BALL_GAP_TOL = 8 };

/* The Model Exchange bouncing ball (restitution 0.8) alone: its bounces are its own state
 * events, no indicator's. */
static ssx_system *own_bounce_system(ssx_fmu **fmu, int stop_at_own_events)
{
    *fmu = load_model_exchange_fmu("bouncing_ball_cvode");
    const unsigned int vr[] = {BALL_E, BALL_GAP_TOL};
    const double values[] = {0.8, 1e-6};
    CHECK(start_fmu(*fmu, 0.0, 1e-12, vr, values, 2) == 0);
    ssx_system *sys = ssx_system_new("ball");
    CHECK(ssx_add_model_exchange_component(sys, "Ball", *fmu, 1, 2, 1) == 0);
    CHECK(ssx_add_output(sys, 0, SSX_REAL, BALL_H) == 0);
    CHECK(ssx_add_output(sys, 0, SSX_REAL, BALL_V) == 1);
    CHECK_OK(sys, ssx_set_stop_at_own_events(sys, stop_at_own_events));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    return sys;
}

/* Asked to, the call stops right after each of the ball's own bounces, at its closed-form time,
 * the ball on the floor going up; the next call goes on to the importer's point. Not asked, the
 * call goes on to t_stop as before. */
static void stops_right_after_an_own_bounce(void)
{
    ssx_fmu *fmu;
    ssx_system *sys = own_bounce_system(&fmu, 1);
    ssx_step_outcome out;
    int bounces = 0;
    for (int k = 1; k <= 30; ++k) {
        double t_stop = k * 0.1;
        do {
            CHECK_OK(sys, ssx_step_until(sys, t_stop, 0.1, &out));
            CHECK(out.status == 0 && !out.terminated && out.time == ssx_time(sys));
            if (out.event) {
                ++bounces;
                CHECK(out.own_event && out.time < t_stop);
                CHECK_CLOSE(out.time, ball_bounce_time(bounces, 0.8), 1e-8);
                ssx_event_record bounce;
                CHECK(ssx_event_count(sys) == (size_t)bounces &&
                      ssx_event_get(sys, (size_t)bounces - 1, &bounce) == 0);
                CHECK(bounce.own == SSX_OWN_STATE_EVENT && bounce.t <= out.time);
                const double *ball = ssx_outputs(sys, 0);
                CHECK(fabs(ball[0]) < 1e-6 && ball[1] > 0.0);
            } else {
                CHECK(!out.own_event && out.time == t_stop);
            }
        } while (out.event);
    }
    CHECK(bounces == 6);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);

    sys = own_bounce_system(&fmu, 0);
    CHECK_OK(sys, ssx_step_until(sys, 3.0, 0.1, &out));
    CHECK(!out.event && !out.own_event && out.time == 3.0 && ssx_event_count(sys) == 6);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    stops_right_after_the_wall_hit();
    stretches_make_the_run();
    a_stop_off_the_grid_cuts_one_step();
    stops_right_after_an_own_bounce();
    return 0;
}
