/* What the statuses of a step mean to a run: an FMU that asks to stop ends it cleanly at the last
 * communication point the whole system completed (plain and hybrid); a discard that is no
 * termination, a failing fmi2GetReal and a non-finite output are failures named precisely. */
#include <math.h>
#include <string.h>

#include "test_support.h"

/* Value references: tests/fmus/Terminating, tests/fmus/Failing, models/Gain. */
enum { TERMINATING_Y = 0, TERMINATING_Y0 = 1, TERMINATING_SLOPE = 2, TERMINATING_STOP = 3 };
enum { FAILING_Y = 0, FAILING_U = 1, FAILING_TIME = 2, FAILING_MODE = 3 };
enum { GAIN_Y = 0, GAIN_U = 1, GAIN_K = 2 };

/* Instantiates and initializes at t = 0 with the given Real parameters. */
static void start(ssx_fmu *fmu, const unsigned int *vr, const double *values, size_t n)
{
    CHECK(start_fmu(fmu, 0.0, 0.0, vr, values, n) == 0);
}

static ssx_fmu *ramp(double y0, double stop_time)
{
    ssx_fmu *fmu = load_fmu("terminating");
    const unsigned int vr[] = {TERMINATING_Y0, TERMINATING_SLOPE, TERMINATING_STOP};
    const double values[] = {y0, 1.0, stop_time};
    start(fmu, vr, values, 3);
    return fmu;
}

static ssx_fmu *failing(int mode)
{
    ssx_fmu *fmu = load_fmu("failing");
    const unsigned int time_vr = FAILING_TIME, mode_vr = FAILING_MODE;
    const double fail_time = 0.5;
    const ssx_fmu_experiment experiment = {.start_time = 0.0};
    const ssx_fmu_values starts = {.real_vr = &time_vr, .real_values = &fail_time, .n_real = 1,
                                   .integer_vr = &mode_vr, .integer_values = &mode,
                                   .n_integer = 1};
    CHECK(ssx_fmu_initialize(fmu, &experiment, &starts, NULL, NULL) == 0);
    return fmu;
}

static int add_one_output(ssx_system *sys, const char *name, ssx_fmu *fmu, unsigned int vr)
{
    int c = ssx_add_fmu_component(sys, name, fmu, 1);
    CHECK(c >= 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, vr) == 0);
    return c;
}

static double last_time(const ssx_system *sys)
{
    return ssx_history_time(sys)[ssx_history_length(sys) - 1];
}

/* Stops inside the step from 0.9 to 1.2: the run ends at 0.9; a new run is refused. */
static void stop_inside_a_step(void)
{
    ssx_fmu *fmu = ramp(0.0, 1.0);
    ssx_system *sys = ssx_system_new("stop inside");
    add_one_output(sys, "ramp", fmu, TERMINATING_Y);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 2.0, 0.3));
    const ssx_termination *end = ssx_get_termination(sys);
    CHECK(end->component == 0);
    CHECK_CLOSE(end->time, 1.0, 0.0);
    CHECK(strstr(end->message, "asks to end the simulation at t = 1") != NULL);
    CHECK(ssx_history_length(sys) == 4);
    CHECK_CLOSE(last_time(sys), 0.9, 1e-15);
    CHECK_CLOSE(ssx_time(sys), 0.9, 1e-15);
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(fmu, &counters);
    CHECK(counters.do_step == 4);

    CHECK(ssx_run(sys, ssx_time(sys), 2.0, 0.3) == -1);
    CHECK_MESSAGE(sys, "system 'stop inside' ended at t=0.89999999999999991: component 'ramp' "
                       "asked to stop at t=1; initialize the system again");
    ssx_fmu_get_counters(fmu, &counters);
    CHECK(counters.do_step == 4);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* Stops at the end of a step: that point is complete, the gain after it steps too. */
static void stop_at_a_communication_point(void)
{
    ssx_fmu *source = ramp(0.0, 1.0);
    ssx_fmu *gain = load_fmu("gain");
    const unsigned int k_vr = GAIN_K;
    const double k = 2.0;
    start(gain, &k_vr, &k, 1);
    ssx_system *sys = ssx_system_new("stop at a point");
    int r = add_one_output(sys, "ramp", source, TERMINATING_Y);
    int g = add_one_output(sys, "gain", gain, GAIN_Y);
    CHECK(ssx_add_input(sys, g, SSX_REAL, GAIN_U, 0.0) == 0);
    CHECK(ssx_connect(sys, r, 0, g, 0, 1.0, 0.0) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 2.0, 0.25));
    CHECK(ssx_get_termination(sys)->component == r);
    CHECK(ssx_history_length(sys) == 5);
    CHECK_CLOSE(last_time(sys), 1.0, 0.0);
    CHECK_CLOSE(ssx_history_values(sys, r)[4], 1.0, 0.0);
    CHECK_CLOSE(ssx_history_values(sys, g)[4], 2.0, 0.0);
    ssx_system_free(sys);
    ssx_fmu_free(source);
    ssx_fmu_free(gain);
}

/* Hybrid: an event before the stop is handled; a crossing in the step that stops is not located
 * (that would step the stopped FMU again), so the run ends at the step's start. */
static void stop_in_hybrid_runs(double y0, size_t samples, double end, size_t events)
{
    ssx_fmu *fmu = ramp(y0, 1.0);
    ssx_system *sys = ssx_system_new("hybrid stop");
    add_one_output(sys, "ramp", fmu, TERMINATING_Y);
    CHECK(ssx_add_indicator_output(sys, 0, 0, 1) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 2.0, 0.25));
    CHECK(ssx_get_termination(sys)->component == 0);
    CHECK_CLOSE(ssx_get_termination(sys)->time, 1.0, 0.0);
    CHECK(ssx_event_count(sys) == events);
    CHECK(ssx_history_length(sys) == samples);
    CHECK_CLOSE(last_time(sys), end, 0.0);
    CHECK_CLOSE(ssx_time(sys), end, 0.0);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static ssx_system *failing_system(ssx_fmu *fmu)
{
    ssx_system *sys = ssx_system_new("failing");
    add_one_output(sys, "broken", fmu, FAILING_Y);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    return sys;
}

static void discard_without_termination(void)
{
    ssx_fmu *fmu = failing(2);
    ssx_system *sys = failing_system(fmu);
    CHECK(ssx_run(sys, 0.0, 1.0, 0.1) == -1);
    CHECK_MESSAGE(sys, "component 'broken': fmi2DoStep from t=0.5 to 0.60000000000000009 "
                       "returned fmi2Discard without asking to terminate: the FMU completed the "
                       "step only up to fmi2LastSuccessfulTime=0.5 (FMU log: fmi2DoStep from");
    CHECK(ssx_last_error(sys)->fmi_status == 2);
    CHECK(ssx_last_error(sys)->component == 0);
    CHECK_CLOSE(ssx_last_error(sys)->time, 0.5, 0.0);
    CHECK(ssx_get_termination(sys)->component == -1);
    CHECK(ssx_history_length(sys) == 6);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* A failing read after the step from 0.5 is reported at the step's end, where the FMU is. */
static void read_failure_at_the_step_end(void)
{
    ssx_fmu *fmu = failing(3);
    ssx_system *sys = failing_system(fmu);
    CHECK(ssx_run(sys, 0.0, 1.0, 0.1) == -1);
    CHECK_MESSAGE(sys, "fmi2GetReal failed at t=0.60000000000000009 with status fmi2Error");
    CHECK_CLOSE(ssx_last_error(sys)->time, 0.6, 1e-15);
    CHECK(ssx_history_length(sys) == 6);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* The failing FMU, its output feeding a gain's input. */
static ssx_system *fed_system(ssx_fmu *fmu, ssx_fmu *gain)
{
    start(gain, NULL, NULL, 0);
    ssx_system *sys = ssx_system_new("fed");
    add_one_output(sys, "broken", fmu, FAILING_Y);
    int g = add_one_output(sys, "gain", gain, GAIN_Y);
    CHECK(ssx_add_input(sys, g, SSX_REAL, GAIN_U, 0.0) == 0);
    CHECK(ssx_connect(sys, 0, 0, g, 0, 1.0, 0.0) == 0);
    return sys;
}

/* A NaN output that feeds an input stops the run; allowed, it is recorded; one that feeds
 * nothing is recorded, and the time it first appeared kept. */
static void non_finite_outputs(void)
{
    ssx_fmu *fmu = failing(4);
    ssx_fmu *gain = load_fmu("gain");
    ssx_system *sys = fed_system(fmu, gain);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_run(sys, 0.0, 1.0, 0.1) == -1);
    CHECK_MESSAGE(sys, "component 'broken': output 0 is nan at t=0.60000000000000009");
    CHECK(ssx_last_error(sys)->output == 0);
    CHECK(ssx_last_error(sys)->component == 0);
    CHECK(ssx_history_length(sys) == 6); /* the samples up to 0.5 stay */
    CHECK(ssx_non_finite_outputs(sys, NULL, NULL, NULL, 0) == 0);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);

    ssx_fmu_free(gain);

    fmu = failing(4);
    sys = ssx_system_new("allowed");
    add_one_output(sys, "broken", fmu, FAILING_Y);
    CHECK_OK(sys, ssx_set_allow_non_finite(sys, 1));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.1));
    CHECK(ssx_history_length(sys) == 11);
    CHECK(ssx_history_values(sys, 0)[5] == 0.0 && isnan(ssx_history_values(sys, 0)[6]));
    CHECK(ssx_non_finite_outputs(sys, NULL, NULL, NULL, 0) == 0); /* allowed: nothing checked */
    ssx_system_free(sys);
    ssx_fmu_free(fmu);

    fmu = failing(4);
    sys = failing_system(fmu);
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.1));
    CHECK(ssx_history_length(sys) == 11);
    CHECK(ssx_history_values(sys, 0)[5] == 0.0 && isnan(ssx_history_values(sys, 0)[6]));
    int component = -1, output = -1;
    double first = 0.0;
    CHECK(ssx_non_finite_outputs(sys, NULL, NULL, NULL, 0) == 1);
    CHECK(ssx_non_finite_outputs(sys, &component, &output, &first, 1) == 1);
    CHECK(component == 0 && output == 0);
    CHECK_CLOSE(first, 0.6, 1e-15);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    stop_inside_a_step();
    stop_at_a_communication_point();
    /* crossing at 0.5: handled; the steps to 0.75 and 1.0 complete; samples 0, 0.25, 0.5 (twice),
     * 0.75, 1.0 */
    stop_in_hybrid_runs(-0.5, 6, 1.0, 1);
    /* crossing at 0.95, in the step that stops: the run ends at 0.75 */
    stop_in_hybrid_runs(-0.95, 4, 0.75, 0);
    discard_without_termination();
    read_failure_at_the_step_end();
    non_finite_outputs();
    puts("engine status: ok");
    return 0;
}
