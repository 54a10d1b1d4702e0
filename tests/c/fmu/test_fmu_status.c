/* What a step's status means: a model that asks to stop (fmi2Discard with fmi2Terminated) and
 * the failure modes of the failing model (fmi2Fatal, a plain fmi2Discard, a failing fmi2Get).
 * Usage: test_fmu_status <binary> <modelDescription.xml> terminating|failing */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmu_harness.h"

typedef struct {
    fmi2GetBooleanStatusTYPE *boolean_status;
    fmi2GetRealStatusTYPE *real_status;
} status_queries;

static status_queries queries(const test_fmu *fmu)
{
    status_queries q;
    void *boolean_status = dlsym(fmu->library, "fmi2GetBooleanStatus");
    void *real_status = dlsym(fmu->library, "fmi2GetRealStatus");
    CHECK(boolean_status != NULL && real_status != NULL);
    memcpy(&q.boolean_status, &boolean_status, sizeof boolean_status);
    memcpy(&q.real_status, &real_status, sizeof real_status);
    return q;
}

static int terminated(const status_queries *q, fmi2Component c)
{
    fmi2Boolean value = fmi2True;
    CHECK_OK(q->boolean_status(c, fmi2Terminated, &value));
    return value != fmi2False;
}

static double last_successful_time(const status_queries *q, fmi2Component c)
{
    double value = NAN;
    CHECK_OK(q->real_status(c, fmi2LastSuccessfulTime, &value));
    return value;
}

/* Stops inside a step at stop_time; a state from before the stop steps on again. */
static void check_terminating(test_fmu *fmu)
{
    status_queries q = queries(fmu);
    const char *names[] = {"slope", "stop_time"};
    const double values[] = {2.0, 1.0};
    fmi2Component c = fmu_start(fmu, 0.0, 0.0, names, values, 2);
    CHECK_OK(fmu->do_step(c, 0.0, 0.4, fmi2False));
    CHECK_OK(fmu->do_step(c, 0.4, 0.4, fmi2False));
    CHECK(!terminated(&q, c));
    fmi2FMUstate before_stop = NULL;
    CHECK_OK(fmu->get_state(c, &before_stop));
    CHECK(fmu->do_step(c, 0.8, 0.4, fmi2False) == fmi2Discard);
    printf("terminating logged: %s\n", fmu->log.last_message);
    CHECK(strstr(fmu->log.last_message, "asks to end the simulation at t = 1") != NULL);
    CHECK(terminated(&q, c));
    CHECK_NEAR("fmi2LastSuccessfulTime [s]", last_successful_time(&q, c), 1.0, 0.0);
    CHECK_NEAR("y at the stop", fmu_get(fmu, c, "y"), 2.0, 0.0);
    /* asked again, the model gives the same answer and does not move */
    CHECK(fmu->do_step(c, 1.0, 0.4, fmi2False) == fmi2Discard);
    CHECK_NEAR("fmi2LastSuccessfulTime after a second request [s]", last_successful_time(&q, c),
               1.0, 0.0);
    CHECK_OK(fmu->set_state(c, before_stop));
    CHECK(!terminated(&q, c));
    CHECK_OK(fmu->do_step(c, 0.8, 0.1, fmi2False));
    CHECK_NEAR("y after stepping from the restored state", fmu_get(fmu, c, "y"), 1.8, 1e-15);
    /* a step ending exactly at stop_time completes and asks to stop */
    CHECK(fmu->do_step(c, 0.9, 0.1, fmi2False) == fmi2Discard);
    CHECK_NEAR("fmi2LastSuccessfulTime of a step ending at stop_time [s]",
               last_successful_time(&q, c), 1.0, 0.0);
    CHECK_OK(fmu->free_state(c, &before_stop));
    fmu->free_instance(c);
}

static fmi2Component start_failing(test_fmu *fmu, int failure)
{
    const char *names[] = {"fail_time"};
    const double values[] = {0.5};
    fmi2Component c = fmu->instantiate("test", fmi2CoSimulation, fmu->guid, "", &fmu->callbacks,
                                       fmi2False, fmi2False);
    CHECK(c != NULL);
    CHECK_OK(fmu->setup_experiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    CHECK_OK(fmu->enter_initialization_mode(c));
    fmu_set(fmu, c, names[0], values[0]);
    fmi2ValueReference failure_vr = fmu_vr(fmu, "failure");
    fmi2Integer mode = failure;
    CHECK_OK(fmu->set_integer(c, &failure_vr, 1, &mode));
    CHECK_OK(fmu->exit_initialization_mode(c));
    for (int k = 0; k < 5; ++k)
        CHECK_OK(fmu->do_step(c, k * 0.1, 0.1, fmi2False));
    return c;
}

static void check_failing(test_fmu *fmu)
{
    status_queries q = queries(fmu);
    fmi2ValueReference y = fmu_vr(fmu, "y");
    double value = 0.0;

    fmi2Component c = start_failing(fmu, 1);
    CHECK(fmu->do_step(c, 0.5, 0.1, fmi2False) == fmi2Fatal);
    printf("fatal: %s\n", fmu->log.last_message);
    CHECK(fmu->get_real(c, &y, 1, &value) == fmi2Error);
    CHECK(strstr(fmu->log.last_message, "not allowed in the fatal state") != NULL);
    fmu->free_instance(c); /* forbidden by FMI 2.0; the FMU says so and frees anyway */
    CHECK(strstr(fmu->log.last_message, "fmi2FreeInstance is not allowed") != NULL);

    c = start_failing(fmu, 2);
    CHECK(fmu->do_step(c, 0.5, 0.1, fmi2False) == fmi2Discard);
    printf("discard: %s\n", fmu->log.last_message);
    CHECK(!terminated(&q, c));
    CHECK_NEAR("fmi2LastSuccessfulTime of a discarded step [s]", last_successful_time(&q, c), 0.5,
               0.0);
    fmu->free_instance(c);

    c = start_failing(fmu, 3);
    CHECK_OK(fmu->get_real(c, &y, 1, &value));
    CHECK_OK(fmu->do_step(c, 0.5, 0.1, fmi2False));
    CHECK(fmu->get_real(c, &y, 1, &value) == fmi2Error);
    printf("read: %s\n", fmu->log.last_message);
    CHECK(strstr(fmu->log.last_message, "fmi2GetReal at t = 0.59999999999999998") != NULL);
    fmu->free_instance(c);

    c = start_failing(fmu, 4);
    fmu_set(fmu, c, "u", 3.0);
    CHECK_NEAR("y before fail_time", fmu_get(fmu, c, "y"), 3.0, 0.0);
    CHECK_OK(fmu->do_step(c, 0.5, 0.1, fmi2False));
    CHECK(isnan(fmu_get(fmu, c, "y")));
    fmu->free_instance(c);
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s <binary> <modelDescription.xml> terminating|failing\n", argv[0]);
        return 2;
    }
    test_fmu fmu;
    fmu_open(&fmu, argv[1], argv[2]);
    if (strcmp(argv[3], "terminating") == 0)
        check_terminating(&fmu);
    else
        check_failing(&fmu);
    fmu_close(&fmu);
    return 0;
}
