/* Model Exchange components integrated by the engine (me_component.c), under AddressSanitizer
 * too: bouncing_ball's bounces are its own state events at the closed-form times without
 * rollback; without a rest threshold the bounces accumulate and the run ends with a Zeno error;
 * a failing FMU's error names the component, the call and the time. Every run frees its CVODE. */
#include <math.h>

#include "test_support.h"

/* models/BouncingBall/bouncing_ball.c */
enum { BALL_H = 0, BALL_V = 1, BALL_E = 5, BALL_GAP_TOL = 8, BALL_STATES = 2, BALL_INDICATORS = 1 };
/* tests/fmus/Failing/failing.c */
enum { FAILING_Y = 0, FAILING_FAIL_TIME = 2 };

#define RESTITUTION 0.8

static ssx_system *ball_system(ssx_fmu *fmu, double gap_tol)
{
    const unsigned int vr[] = {BALL_E, BALL_GAP_TOL};
    const double values[] = {RESTITUTION, gap_tol};
    CHECK(start_fmu(fmu, 0.0, 1e-12, vr, values, 2) == 0);
    ssx_system *sys = ssx_system_new("ball");
    int c = ssx_add_model_exchange_component(sys, "Ball", fmu, 1, BALL_STATES, BALL_INDICATORS);
    CHECK(c == 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, BALL_H) == 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, BALL_V) == 1);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    return sys;
}

static void bounces_at_the_closed_form_times(void)
{
    ssx_fmu *fmu = load_model_exchange_fmu("bouncing_ball_cvode");
    ssx_system *sys = ball_system(fmu, 1e-6);
    check_own_bounces(sys);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static void endless_bounces_are_zeno(void)
{
    ssx_fmu *fmu = load_model_exchange_fmu("bouncing_ball_cvode");
    ssx_system *sys = ball_system(fmu, 0.0);
    CHECK(ssx_run(sys, 0.0, 5.0, 0.01) != 0);
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_ZENO);
    CHECK_MESSAGE(sys, "component 'Ball': its event indicator 0 crossed again at t=4.0637");
    CHECK_MESSAGE(sys, "chattering (Zeno) behaviour; the minimum interval is 1e-08");
    /* the samples before the failure stay */
    CHECK(ssx_history_length(sys) > 400);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static void a_failing_call_names_component_call_and_time(void)
{
    ssx_fmu *fmu = load_model_exchange_fmu("failing");
    const unsigned int vr[] = {FAILING_FAIL_TIME};
    const double values[] = {0.25};
    CHECK(start_fmu(fmu, 0.0, 0.0, vr, values, 1) == 0);
    ssx_system *sys = ssx_system_new("failing");
    CHECK(ssx_add_model_exchange_component(sys, "F", fmu, 1, 0, 0) == 0);
    CHECK(ssx_add_output(sys, 0, SSX_REAL, FAILING_Y) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_run(sys, 0.0, 1.0, 0.1) != 0);
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_FMI);
    CHECK_MESSAGE(sys, "component 'F': fmi2SetTime failed at t=0.30000000000000004 with status "
                       "fmi2Error (FMU log: ");
    CHECK(ssx_history_length(sys) == 3); /* 0, 0.1, 0.2 */
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static void refuses_a_co_simulation_fmu(void)
{
    ssx_fmu *fmu = load_fmu("bouncing_ball_cvode");
    ssx_system *sys = ssx_system_new("wrong");
    CHECK(ssx_add_model_exchange_component(sys, "Ball", fmu, 1, 2, 1) < 0);
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_CONFIG);
    CHECK_MESSAGE(sys, "component 'Ball': the FMU was not loaded for Model Exchange");
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    bounces_at_the_closed_form_times();
    endless_bounces_are_zeno();
    a_failing_call_names_component_call_and_time();
    refuses_a_co_simulation_fmu();
    return 0;
}
