/* Every misuse returns fmi2Error and logs a message saying why.
 * Usage: test_fmu_errors <binary> <modelDescription.xml> (a pendulum FMU) */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmu_harness.h"

/* The call failed with fmi2Error and a new error message containing `expected` was logged. */
static void check_error(test_fmu *fmu, fmi2Status status, int count_before, const char *expected)
{
    printf("%-28s -> status %d, message: %s\n", expected, status, fmu->log.last_message);
    CHECK(status == fmi2Error);
    CHECK(fmu->log.count > count_before);
    CHECK(fmu->log.last_status == fmi2Error);
    CHECK(strcmp(fmu->log.last_category, "logStatusError") == 0);
    CHECK(strstr(fmu->log.last_message, expected) != NULL);
}

#define EXPECT_ERROR(call, expected)                        \
    do {                                                    \
        int before = fmu->log.count;                        \
        check_error(fmu, (call), before, (expected));       \
    } while (0)

static void check_refused_instantiation(test_fmu *fmu)
{
    int before = fmu->log.count;
    fmi2Component c = fmu->instantiate("test", fmi2CoSimulation, "{not-this-fmu}", "",
                                       &fmu->callbacks, fmi2False, fmi2False);
    CHECK(c == NULL);
    check_error(fmu, fmi2Error, before, "GUID");
    before = fmu->log.count;
    c = fmu->instantiate("test", (fmi2Type)7, fmu->guid, "", &fmu->callbacks, fmi2False,
                         fmi2False);
    CHECK(c == NULL);
    check_error(fmu, fmi2Error, before, "fmuType 7 is neither fmi2ModelExchange");
}

static void check_call_order(test_fmu *fmu)
{
    fmi2Component c = fmu->instantiate("test", fmi2CoSimulation, fmu->guid, "", &fmu->callbacks,
                                       fmi2False, fmi2False);
    CHECK(c != NULL);
    EXPECT_ERROR(fmu->do_step(c, 0.0, 0.1, fmi2False), "not allowed in instantiated");
    EXPECT_ERROR(fmu->exit_initialization_mode(c), "not allowed in instantiated");
    CHECK_OK(fmu->setup_experiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    CHECK_OK(fmu->enter_initialization_mode(c));
    EXPECT_ERROR(fmu->setup_experiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0),
                 "not allowed in initialization mode");
    CHECK_OK(fmu->exit_initialization_mode(c));
    EXPECT_ERROR(fmu->enter_initialization_mode(c), "not allowed in step mode");
    CHECK_OK(fmu->terminate(c));
    EXPECT_ERROR(fmu->do_step(c, 0.0, 0.1, fmi2False), "not allowed in terminated");
    fmu->free_instance(c);
}

static void check_bad_arguments(test_fmu *fmu)
{
    fmi2Component c = fmu_start(fmu, 0.0, 0.0, NULL, NULL, 0);
    EXPECT_ERROR(fmu->do_step(c, 0.0, -0.1, fmi2False), "negative or not finite");
    EXPECT_ERROR(fmu->do_step(c, 0.0, NAN, fmi2False), "negative or not finite");
    EXPECT_ERROR(fmu->do_step(c, 0.5, 0.1, fmi2False), "differs from the FMU's time");
    fmi2ValueReference unknown = 999;
    double value = 0.0;
    EXPECT_ERROR(fmu->get_real(c, &unknown, 1, &value), "unknown value reference 999");
    EXPECT_ERROR(fmu->set_real(c, &unknown, 1, &value), "unknown value reference 999");
    fmi2ValueReference theta = fmu_vr(fmu, "theta");
    fmi2Integer integer = 0;
    EXPECT_ERROR(fmu->get_integer(c, &theta, 1, &integer), "is of type Real");
    EXPECT_ERROR(fmu->set_real(c, &theta, 1, &value), "cannot be set");
    fmi2ValueReference mass = fmu_vr(fmu, "m");
    double heavier = 50.0;
    EXPECT_ERROR(fmu->set_real(c, &mass, 1, &heavier), "fixed parameter");
    CHECK_NEAR("m after the refused set", fmu_get(fmu, c, "m"), 40.0, 0.0);
    /* the instance stays usable after refused calls */
    CHECK_OK(fmu->do_step(c, 0.0, 0.1, fmi2False));
    fmu->free_instance(c);
}

/* loggingOn and the categories filter information, errors stay visible unless switched off. */
static void check_logging_filter(test_fmu *fmu)
{
    fmi2Component c = fmu_start(fmu, 0.0, 0.0, NULL, NULL, 0);
    const char *unknown[] = {"logNothing"};
    EXPECT_ERROR(fmu->set_debug_logging(c, fmi2True, 1, unknown), "unknown log category");
    const char *events_only[] = {"logEvents"};
    CHECK_OK(fmu->set_debug_logging(c, fmi2True, 1, events_only));
    int before = fmu->log.count;
    CHECK(fmu->do_step(c, 0.0, -1.0, fmi2False) == fmi2Error);
    CHECK(fmu->log.count == before); /* logStatusError is not among the chosen categories */
    CHECK_OK(fmu->set_debug_logging(c, fmi2False, 0, NULL));
    EXPECT_ERROR(fmu->do_step(c, 0.0, -1.0, fmi2False), "negative");
    fmu->free_instance(c);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s <binary> <modelDescription.xml>\n", argv[0]);
        return 2;
    }
    test_fmu fmu;
    fmu_open(&fmu, argv[1], argv[2]);
    check_refused_instantiation(&fmu);
    check_call_order(&fmu);
    check_bad_arguments(&fmu);
    check_logging_filter(&fmu);
    fmu_close(&fmu);
    return 0;
}
