/* The declarative restart handler (ssx_set_restart_handler): the master's bouncing ball of
 * engine_bouncing_ball.c with its bounce (h0 = h, v0 = -0.8 v) described instead of written as
 * a hook. The first ten bounce times against the closed form; one instance, reset at each
 * bounce; a start value given with the handler is written at every restart; bad sources are
 * refused. */
#include <math.h>

#include "test_support.h"

enum { BALL_H = 0, BALL_V = 1, BALL_G = 4, BALL_H0 = 5, BALL_V0 = 6 };

#define RESTITUTION 0.8
#define BOUNCES 10

static void bounces_on_the_closed_form(void)
{
    ssx_fmu *fmu = load_fmu("bouncing_ball_continuous_cvode");
    const unsigned int start_vr[] = {BALL_H0, BALL_V0};
    const double start_values[] = {1.0, 0.0};
    CHECK(start_fmu(fmu, 0.0, 1e-10, start_vr, start_values, 2) == 0);
    ssx_system *sys = ssx_system_new("ball");
    int ball = ssx_add_fmu_component(sys, "Ball", fmu, 1);
    CHECK(ssx_add_output(sys, ball, SSX_REAL, BALL_H) == BALL_H);
    CHECK(ssx_add_output(sys, ball, SSX_REAL, BALL_V) == BALL_V);
    CHECK(ssx_add_indicator_output(sys, ball, BALL_H, -1) == 0);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, ball));
    const ssx_fmu_experiment experiment = {.tolerance_defined = 1, .tolerance = 1e-10};
    /* g written at every restart: the model's own value, so the closed form holds */
    const unsigned int g_vr = BALL_G;
    const double g = 9.81;
    const ssx_fmu_values starts = {.real_vr = &g_vr, .real_values = &g, .n_real = 1};
    const int source[] = {BALL_H, BALL_V};
    const double scale[] = {1.0, -RESTITUTION}, offset[] = {0.0, 0.0};
    CHECK(ssx_set_restart_handler(sys, ball, &experiment, &starts, start_vr, (const int[]){7, 0},
                                  scale, offset, 2) == -1); /* no output 7 */
    CHECK_OK(sys, ssx_set_restart_handler(sys, ball, &experiment, &starts, start_vr, source,
                                          scale, offset, 2));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, 1e-10, 1e-10, 100, 10, 0, SSX_ILLINOIS, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    double tf =
        0.5 * (ball_bounce_time(BOUNCES, RESTITUTION) + ball_bounce_time(BOUNCES + 1, RESTITUTION));
    CHECK_OK(sys, ssx_run(sys, 0.0, tf, 0.05));

    CHECK(ssx_event_count(sys) == BOUNCES);
    for (int k = 1; k <= BOUNCES; ++k) {
        ssx_event_record event;
        CHECK(ssx_event_get(sys, (size_t)k - 1, &event) == 0);
        CHECK_CLOSE(event.t, ball_bounce_time(k, RESTITUTION), 1e-8);
    }
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(fmu, &counters);
    CHECK(counters.instantiate == 1 && counters.reset == BOUNCES);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    bounces_on_the_closed_form();
    return 0;
}
