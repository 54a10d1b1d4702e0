/* Error paths: each failure returns -1 and an error that names what failed, where and when. */
#include <math.h>
#include <string.h>

#include "test_support.h"

static void bad_input(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    ssx_fmu *other = load_fmu("pendulum_euler");
    CHECK(start_pendulum(fmu, 0.0, 0.5, 0.0, 0.0) == 0);
    CHECK(start_pendulum(other, 0.0, 0.2, 0.0, 0.0) == 0);
    ssx_system *sys = ssx_system_new("errors");
    int a = add_pendulum(sys, "first", fmu);
    int b = add_pendulum(sys, "second", other);

    CHECK(ssx_add_output(sys, 5, SSX_REAL, 0) == -1);
    CHECK_MESSAGE(sys, "unknown component index 5");
    CHECK(ssx_last_error(sys)->component == -1);
    CHECK(ssx_outputs(sys, -1) == NULL);

    CHECK(ssx_add_fmu_component(sys, "first", fmu, 1) == -1);
    CHECK_MESSAGE(sys, "already has a component named 'first'");

    CHECK(ssx_connect(sys, a, 0, b, 0, 1.0, 0.0) == 0);
    CHECK(ssx_connect(sys, a, 1, b, 0, 1.0, 0.0) == -1);
    CHECK_MESSAGE(sys, "input 0 of component 'second' is already driven by output 0 of "
                       "component 'first'");
    CHECK(ssx_last_error(sys)->component == b);
    CHECK(ssx_connect(sys, a, 3, b, 0, 1.0, 0.0) == -1);
    CHECK_MESSAGE(sys, "component 'first' has no output 3");
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_CONFIG);

    CHECK(ssx_run(sys, 0.0, 1.0, 0.1) == -1);
    CHECK_MESSAGE(sys, "not initialized");

    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_run(sys, 0.0, 1.0, 0.0) == -1);
    CHECK_MESSAGE(sys, "dt must be positive");
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_CONFIG);
    CHECK(ssx_run(sys, 0.0, 1.0, -0.1) == -1);
    CHECK_MESSAGE(sys, "dt must be positive");
    CHECK(ssx_run(sys, 0.0, 1.0, NAN) == -1);
    CHECK_MESSAGE(sys, "must be finite");
    CHECK(ssx_run(sys, 0.0, INFINITY, 0.1) == -1);
    CHECK_MESSAGE(sys, "must be finite");
    CHECK(ssx_run(sys, 1.0, 0.5, 0.1) == -1);
    CHECK_MESSAGE(sys, "tf=0.5 lies before t0=1");
    CHECK(ssx_run(sys, 0.5, 1.0, 0.1) == -1);
    CHECK_MESSAGE(sys, "a run must start there");
    /* nothing above touched the FMUs or the history */
    CHECK(ssx_history_length(sys) == 1);
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(fmu, &counters);
    CHECK(counters.do_step == 0);

    const int order[] = {b, a};
    const int sizes[] = {2};
    CHECK(ssx_set_schedule(sys, order, sizes, NULL, 1) == 0);
    const int twice[] = {a, a};
    CHECK(ssx_set_schedule(sys, twice, sizes, NULL, 1) == -1);
    CHECK_MESSAGE(sys, "every component exactly once");
    ssx_fmu *third = load_fmu("pendulum_euler");
    CHECK(start_pendulum(third, 0.0, 0.1, 0.0, 0.0) == 0);
    add_pendulum(sys, "third", third);
    CHECK(ssx_initialize(sys, 0.0) == -1);
    CHECK_MESSAGE(sys, "the schedule lists 2 components but the system now has 3");

    CHECK(ssx_set_hybrid_options(sys, 0.0, 1e-9, 10, 10, 0, SSX_ILLINOIS, 0.0) == -1);
    CHECK(ssx_set_loop_options(sys, 1e-9, 10, 1.5) == -1);
    CHECK(ssx_add_indicator_output(sys, a, 0, 2) == -1);
    CHECK_MESSAGE(sys, "direction must be -1, 0 or +1");
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
    ssx_fmu_free(other);
    ssx_fmu_free(third);
}

enum { FAILING_Y = 0, FAILING_U = 1 };

static void failing_fmu_call(void)
{
    ssx_fmu *fmu = load_fmu("failing");
    CHECK(start_fmu(fmu, 0.0, 0.0, NULL, NULL, 0) == 0);
    ssx_system *sys = ssx_system_new("failing");
    int c = ssx_add_fmu_component(sys, "Breaker", fmu, 1);
    CHECK(ssx_add_output(sys, c, SSX_REAL, FAILING_Y) == 0);
    CHECK(ssx_add_input(sys, c, SSX_REAL, FAILING_U, 2.5) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_outputs(sys, c)[0] == 2.5); /* the input's start value, not a type default */

    CHECK(ssx_run(sys, 0.0, 2.0, 0.25) == -1); /* fail_time is 1 */
    const ssx_error *e = ssx_last_error(sys);
    printf("%s\n", e->message);
    CHECK_MESSAGE(sys, "component 'Breaker'");
    CHECK_MESSAGE(sys, "fmi2DoStep");
    CHECK_MESSAGE(sys, "t=1");
    CHECK_MESSAGE(sys, "fmi2Error");
    CHECK_MESSAGE(sys, "fail_time"); /* the FMU's own log message */
    CHECK(e->component == c && e->fmi_status == 3 && e->time == 1.0 && e->kind == SSX_ERROR_FMI);
    /* the samples recorded before the failure stay readable */
    CHECK(ssx_history_length(sys) == 5);
    CHECK(ssx_history_time(sys)[4] == 1.0);
    CHECK(ssx_history_values(sys, c)[4] == 2.5);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static int refuse(void *user, double t, double dt)
{
    (void)user;
    (void)t;
    (void)dt;
    return -1;
}

static int pass_through(void *user, double t)
{
    (void)user;
    (void)t;
    return 0;
}

static void failing_hook(void)
{
    ssx_system *sys = ssx_system_new("hooks");
    int c = ssx_add_python_component(sys, "Scripted", 0);
    CHECK(ssx_initialize(sys, 0.0) == -1);
    CHECK_MESSAGE(sys, "needs do_step and evaluate_outputs hooks");
    ssx_hooks hooks = {.do_step = refuse, .evaluate_outputs = pass_through};
    CHECK_OK(sys, ssx_set_hooks(sys, c, &hooks));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_run(sys, 0.0, 1.0, 0.5) == -1);
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_CALLBACK);
    CHECK_MESSAGE(sys, "component 'Scripted': the Python do_step hook failed at t=0");

    /* an indicator on a component that cannot roll back is refused before anything runs */
    CHECK(ssx_add_output(sys, c, SSX_REAL, 0) == 0);
    CHECK(ssx_add_indicator_output(sys, c, 0, 0) == 0);
    CHECK(ssx_initialize(sys, 0.0) == -1);
    CHECK_MESSAGE(sys, "component 'Scripted' cannot save and restore its state");
    ssx_system_free(sys);
}

/* The defaults are one set of values the setters accept (Python's option classes read them). */
static void defaults_are_valid_options(void)
{
    ssx_defaults d;
    ssx_get_defaults(&d);
    CHECK(d.loop_max_iterations == 100 && d.max_iterations == 100 && d.output_interval == 1);
    ssx_system *sys = ssx_system_new("defaults");
    CHECK_OK(sys, ssx_set_coupling(sys, d.coupling));
    CHECK_OK(sys,
             ssx_set_loop_options(sys, d.loop_tolerance, d.loop_max_iterations, d.loop_damping));
    CHECK_OK(sys, ssx_set_loop_jacobian(sys, d.loop_jacobian));
    CHECK_OK(sys, ssx_set_hybrid_options(sys, d.tol_time, d.tol_value, d.max_iterations,
                                         d.max_microsteps, 0, d.locator, d.zeno_min_interval));
    CHECK_OK(sys, ssx_set_output_interval(sys, d.output_interval));
    CHECK(ssx_set_hybrid_options(sys, -1.0, d.tol_value, d.max_iterations, d.max_microsteps, 0,
                                 d.locator, d.zeno_min_interval) == -1);
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_CONFIG);
    ssx_system_free(sys);
}

int main(void)
{
    defaults_are_valid_options();
    bad_input();
    failing_fmu_call();
    failing_hook();
    return 0;
}
