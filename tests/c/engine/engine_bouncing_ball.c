/* A bouncing ball whose bounce is handled by the master (the FMU only falls): the first ten
 * bounce times against the closed form, with the indicator h listening to falling crossings and
 * to both directions. Both must bounce, never fall through, never fire on the way up. */
#include <math.h>

#include "test_support.h"

enum { BALL_H = 0, BALL_V = 1, BALL_G = 4, BALL_H0 = 5, BALL_V0 = 6 };

#define RESTITUTION 0.8
#define BOUNCES 10

typedef struct {
    ssx_system *sys;
    ssx_fmu *fmu;
    int component;
} ball;

static int start_ball(ssx_fmu *fmu, double t, double h0, double v0)
{
    const unsigned int vr[] = {BALL_H0, BALL_V0};
    const double values[] = {h0, v0};
    return start_fmu(fmu, t, 1e-10, vr, values, 2);
}

static int bounce(void *user, const int *indicators, int n, double t)
{
    (void)indicators;
    (void)n;
    ball *b = user;
    const double *out = ssx_outputs(b->sys, b->component);
    return start_ball(b->fmu, t, out[BALL_H], -RESTITUTION * out[BALL_V]) == 0 ? 0 : -1;
}

static void run(int direction)
{
    ssx_fmu *fmu = load_fmu("bouncing_ball_continuous_cvode");
    CHECK(start_ball(fmu, 0.0, 1.0, 0.0) == 0);
    ssx_system *sys = ssx_system_new("ball");
    ball b = {.sys = sys, .fmu = fmu};
    b.component = ssx_add_fmu_component(sys, "Ball", fmu, 1);
    CHECK(ssx_add_output(sys, b.component, SSX_REAL, BALL_H) == BALL_H);
    CHECK(ssx_add_output(sys, b.component, SSX_REAL, BALL_V) == BALL_V);
    CHECK(ssx_add_indicator_output(sys, b.component, BALL_H, direction) == 0);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, b.component));
    ssx_hooks hooks = {.user = &b, .handle_events = bounce};
    CHECK_OK(sys, ssx_set_hooks(sys, b.component, &hooks));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, 1e-10, 1e-10, 100, 10, 0, SSX_ILLINOIS, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    double tf =
        0.5 * (ball_bounce_time(BOUNCES, RESTITUTION) + ball_bounce_time(BOUNCES + 1, RESTITUTION));
    CHECK_OK(sys, ssx_run(sys, 0.0, tf, 0.05));

    CHECK(ssx_event_count(sys) == BOUNCES);
    for (int k = 1; k <= BOUNCES; ++k) {
        ssx_event_record event;
        CHECK(ssx_event_get(sys, (size_t)k - 1, &event) == 0);
        CHECK(event.micro == 0);
        /* CVODE at rtol 1e-10 and tol_time 1e-10 per bounce; the restart error adds up */
        CHECK_CLOSE(event.t, ball_bounce_time(k, RESTITUTION), 1e-8);
    }
    /* never below the floor by more than the localization residue */
    const double *values = ssx_history_values(sys, b.component);
    for (size_t k = 0; k < ssx_history_length(sys); ++k) {
        CHECK(values[k * 2 + BALL_H] > -1e-8);
    }
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    run(-1);
    run(0);
    return 0;
}
