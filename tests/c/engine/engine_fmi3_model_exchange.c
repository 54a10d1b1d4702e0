/* FMI 3.0 Model Exchange components (the FMI 3.0 back-end's Model Exchange calls, driven by
 * me_component.c), under AddressSanitizer too: the FMI 3.0 bouncing ball's bounces are its own
 * state events at the closed-form times without rollback; an instance that counts other event
 * indicators than the component was given fails naming both counts and the fmi3 call; an FMI
 * 3.0 Co-Simulation load is not a Model Exchange FMU. */
#include <math.h>

#include "test_support.h"

/* models/BouncingBall/bouncing_ball.c */
enum { BALL_H = 0, BALL_V = 1, BALL_E = 5, BALL_GAP_TOL = 8, BALL_STATES = 2, BALL_INDICATORS = 1 };

#define RESTITUTION 0.8

static const unsigned int ball_vr[] = {BALL_H, BALL_V, BALL_E, BALL_GAP_TOL};
static const unsigned char ball_types[] = {SSX_FMI3_FLOAT64, SSX_FMI3_FLOAT64, SSX_FMI3_FLOAT64,
                                           SSX_FMI3_FLOAT64};
static const char *const ball_names[] = {"h", "v", "e", "gap_tol"};
static const ssx_fmi3_variables ball_variables = {
    .vr = ball_vr, .type = ball_types, .name = ball_names, .n = 4};

static ssx_system *ball_system(ssx_fmu *fmu, int n_event_indicators)
{
    const unsigned int vr[] = {BALL_E, BALL_GAP_TOL};
    const double values[] = {RESTITUTION, 1e-6};
    CHECK(start_fmu(fmu, 0.0, 1e-12, vr, values, 2) == 0);
    ssx_system *sys = ssx_system_new("ball");
    int c = ssx_add_model_exchange_component(sys, "Ball", fmu, 1, BALL_STATES,
                                             n_event_indicators);
    CHECK(c == 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, BALL_H) == 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, BALL_V) == 1);
    return sys;
}

static void bounces_at_the_closed_form_times(void)
{
    ssx_fmu *fmu = load_fmi3_fmu("bouncing_ball_cvode_fmi3", &ball_variables, 1);
    ssx_system *sys = ball_system(fmu, BALL_INDICATORS);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    check_own_bounces(sys);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static void another_count_of_event_indicators_is_refused(void)
{
    ssx_fmu *fmu = load_fmi3_fmu("bouncing_ball_cvode_fmi3", &ball_variables, 1);
    ssx_system *sys = ball_system(fmu, 0);
    CHECK(ssx_initialize(sys, 0.0) != 0);
    CHECK_MESSAGE(sys, "component 'Ball': event indicators: the instance has 1 "
                       "(fmi3GetNumberOfEventIndicators at t=0), its modelDescription declares 0");
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static void refuses_a_co_simulation_load(void)
{
    ssx_fmu *fmu = load_fmi3_fmu("bouncing_ball_cvode_fmi3", &ball_variables, 0);
    ssx_system *sys = ssx_system_new("ball");
    CHECK(ssx_add_model_exchange_component(sys, "Ball", fmu, 1, BALL_STATES, BALL_INDICATORS) <
          0);
    CHECK_MESSAGE(sys, "component 'Ball': the FMU was not loaded for Model Exchange");
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    bounces_at_the_closed_form_times();
    another_count_of_event_indicators_is_refused();
    refuses_a_co_simulation_load();
    return 0;
}
