/* Members run by the engine (ssx_run_members): the bouncing ball with its declarative restart,
 * members varying h0 (a start value the restart takes from the outputs instead) and g (a start
 * value the restart writes again). Each member's samples equal, bit for bit, those of the same
 * member started by hand (ssx_fmu_enter_initialization with its values, the restart set with
 * them, ssx_initialize, ssx_run); one instance serves every member (reset); a column that is
 * not among the start values is refused. */
#include <stdlib.h>
#include <string.h>

#include "test_support.h"

enum { BALL_H = 0, BALL_V = 1, BALL_G = 4, BALL_H0 = 5, BALL_V0 = 6 };

#define MEMBERS 3
#define TF 2.0
#define DT 0.05

static const double member_values[MEMBERS][2] = {{1.0, 9.81}, {2.0, 9.81}, {1.5, 3.7}};
static const ssx_fmu_experiment experiment = {.tolerance_defined = 1, .tolerance = 1e-10};
static const int source[] = {BALL_H, BALL_V};
static const double scale[] = {1.0, -0.8}, offset[] = {0.0, 0.0};
static const unsigned int restart_vr[] = {BALL_H0, BALL_V0};

static ssx_system *ball_system(ssx_fmu *fmu)
{
    ssx_system *sys = ssx_system_new("ball");
    int ball = ssx_add_fmu_component(sys, "Ball", fmu, 1);
    CHECK(ssx_add_output(sys, ball, SSX_REAL, BALL_H) == BALL_H);
    CHECK(ssx_add_output(sys, ball, SSX_REAL, BALL_V) == BALL_V);
    CHECK(ssx_add_indicator_output(sys, ball, BALL_H, -1) == 0);
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, ball));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, 1e-10, 1e-10, 100, 10, 0, SSX_ILLINOIS, 0.0));
    return sys;
}

/* The start values of a member: h0, v0 = 0, g; the restart's: g. */
static void member_starts(const double *values, double starts[3], ssx_fmu_values *initial,
                          ssx_fmu_values *restart)
{
    static const unsigned int vr[] = {BALL_H0, BALL_V0, BALL_G};
    starts[0] = values[0];
    starts[1] = 0.0;
    starts[2] = values[1];
    *initial = (ssx_fmu_values){.real_vr = vr, .real_values = starts, .n_real = 3};
    *restart = (ssx_fmu_values){.real_vr = vr + 2, .real_values = starts + 2, .n_real = 1};
}

/* Member k by hand: its samples as rows of (t, h, v), and their number. */
static size_t by_hand(int k, double **rows)
{
    ssx_fmu *fmu = load_fmu("bouncing_ball_continuous_cvode");
    ssx_system *sys = ball_system(fmu);
    double starts[3];
    ssx_fmu_values initial, restart;
    member_starts(member_values[k], starts, &initial, &restart);
    ssx_fmu_experiment at_t0 = experiment;
    CHECK(ssx_fmu_enter_initialization(fmu, &at_t0, &initial, NULL, NULL) == 0);
    CHECK_OK(sys, ssx_set_restart_handler(sys, 0, &experiment, &restart, restart_vr, source,
                                          scale, offset, 2));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, TF, DT));
    size_t n = ssx_history_length(sys);
    *rows = malloc(n * 3 * sizeof **rows);
    CHECK(*rows != NULL);
    const double *t = ssx_history_time(sys), *values = ssx_history_values(sys, 0);
    for (size_t j = 0; j < n; ++j) {
        (*rows)[3 * j] = t[j];
        (*rows)[3 * j + 1] = values[2 * j];
        (*rows)[3 * j + 2] = values[2 * j + 1];
    }
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
    return n;
}

static void members_match_members_by_hand(void)
{
    ssx_fmu *fmu = load_fmu("bouncing_ball_continuous_cvode");
    ssx_system *sys = ball_system(fmu);
    double starts[3];
    ssx_fmu_values initial, restart;
    member_starts(member_values[0], starts, &initial, &restart);
    CHECK(ssx_fmu_enter_initialization(fmu, &experiment, &initial, NULL, NULL) == 0);
    CHECK_OK(sys, ssx_set_restart_handler(sys, 0, &experiment, &restart, restart_vr, source,
                                          scale, offset, 2));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));

    const int component[] = {0, 0}, type[] = {SSX_REAL, SSX_REAL};
    const unsigned int vr[] = {BALL_H0, BALL_G};
    ssx_members *unknown = ssx_members_new(sys, 1, component, type, (unsigned int[]){BALL_H},
                                           (int[]){0});
    CHECK(unknown != NULL);
    CHECK(ssx_members_set_start(unknown, 0, &experiment, &initial) == -1);
    CHECK_MESSAGE(sys, "not among its start values");
    ssx_members_free(unknown);

    ssx_members *members = ssx_members_new(sys, 2, component, type, vr, (int[]){0, 1});
    CHECK(members != NULL);
    CHECK_OK(sys, ssx_members_set_start(members, 0, &experiment, &initial));
    CHECK_OK(sys, ssx_run_members(members, MEMBERS, &member_values[0][0], 0.0, TF, DT));
    const double *rows;
    const int *micro;
    const size_t *bounds;
    size_t width;
    CHECK(ssx_members_samples(members, &rows, &micro, &bounds, &width) == MEMBERS);
    CHECK(width == 3);
    for (int k = 0; k < MEMBERS; ++k) {
        double *expected;
        size_t n = by_hand(k, &expected);
        CHECK(bounds[k + 1] - bounds[k] == n);
        CHECK(memcmp(rows + bounds[k] * width, expected, n * width * sizeof *rows) == 0);
        free(expected);
    }
    /* the members' bounces differ: g and h0 were written */
    CHECK(rows[(bounds[1] - 1) * width + 1] != rows[(bounds[2] - 1) * width + 1]);
    CHECK(rows[(bounds[2] - 1) * width + 1] != rows[(bounds[3] - 1) * width + 1]);
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(fmu, &counters);
    CHECK(counters.instantiate == 1);
    ssx_members_free(members);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    members_match_members_by_hand();
    return 0;
}
