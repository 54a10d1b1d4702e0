/* A minimal FMI 2.0 Co-Simulation master for the FMU tests: loads a built FMU binary with dlopen,
 * reads its GUID and value references from its modelDescription.xml, records its log messages. */
#ifndef SYSSIMX_TEST_FMU_HARNESS_H
#define SYSSIMX_TEST_FMU_HARNESS_H

#include <stddef.h>

#include "fmi2Functions.h"

typedef struct {
    int count;               /* messages received */
    fmi2Status last_status;
    char last_category[64];
    char last_message[1024];
} log_record;

typedef struct {
    void *library;
    char *description;       /* modelDescription.xml text */
    char guid[64];
    log_record log;
    fmi2CallbackFunctions callbacks;
    fmi2InstantiateTYPE *instantiate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2SetDebugLoggingTYPE *set_debug_logging;
    fmi2SetupExperimentTYPE *setup_experiment;
    fmi2EnterInitializationModeTYPE *enter_initialization_mode;
    fmi2ExitInitializationModeTYPE *exit_initialization_mode;
    fmi2TerminateTYPE *terminate;
    fmi2ResetTYPE *reset;
    fmi2GetRealTYPE *get_real;
    fmi2SetRealTYPE *set_real;
    fmi2GetIntegerTYPE *get_integer;
    fmi2SetIntegerTYPE *set_integer;
    fmi2GetBooleanTYPE *get_boolean;
    fmi2DoStepTYPE *do_step;
    fmi2GetFMUstateTYPE *get_state;
    fmi2SetFMUstateTYPE *set_state;
    fmi2FreeFMUstateTYPE *free_state;
    fmi2SerializedFMUstateSizeTYPE *serialized_size;
    fmi2SerializeFMUstateTYPE *serialize;
    fmi2DeSerializeFMUstateTYPE *deserialize;
    fmi2GetDerivativesTYPE *get_derivatives;
    /* Model Exchange */
    fmi2SetTimeTYPE *set_time;
    fmi2SetContinuousStatesTYPE *set_continuous_states;
    fmi2GetContinuousStatesTYPE *get_continuous_states;
    fmi2GetEventIndicatorsTYPE *get_event_indicators;
    fmi2EnterEventModeTYPE *enter_event_mode;
    fmi2NewDiscreteStatesTYPE *new_discrete_states;
    fmi2EnterContinuousTimeModeTYPE *enter_continuous_time_mode;
} test_fmu;

/* Exits the test with a message when the binary or the description cannot be used. */
void fmu_open(test_fmu *fmu, const char *binary_path, const char *description_path);
void fmu_close(test_fmu *fmu);

/* The value reference of a named variable (the test fails when there is none). */
fmi2ValueReference fmu_vr(const test_fmu *fmu, const char *name);

/* Instantiate, set up (tolerance <= 0: undefined) at t0, set the named Real start values and
 * initialize. */
fmi2Component fmu_start(test_fmu *fmu, double tolerance, double t0, const char *const names[],
                        const double values[], size_t n);

double fmu_get(test_fmu *fmu, fmi2Component c, const char *name);
void fmu_set(test_fmu *fmu, fmi2Component c, const char *name, double value);

/* Fails the test (exit 1) with the location when the condition is false. */
#define CHECK(condition) check_that((condition), #condition, __FILE__, __LINE__)
#define CHECK_OK(call) CHECK((call) == fmi2OK)
void check_that(int condition, const char *text, const char *file, int line);

/* |actual - expected| <= tolerance, printing both values either way. */
#define CHECK_NEAR(label, actual, expected, tolerance) \
    check_near((label), (actual), (expected), (tolerance), __FILE__, __LINE__)
void check_near(const char *label, double actual, double expected, double tolerance,
                const char *file, int line);

/* The first time after t_from (a grid time of c) at which predicate(value of `name`) holds,
 * located by stepping with step `dt` and then bisecting the step length over a saved state
 * until the bracket is below `resolution`. Leaves c just past the event, at *t_now. */
typedef int (*value_predicate)(double value);
double fmu_find_time(test_fmu *fmu, fmi2Component c, double t_from, double dt, double t_max,
                     const char *name, value_predicate predicate, double resolution,
                     double *t_now);

/* Complete elliptic integral of the first kind K(m), m = k^2, by the arithmetic-geometric mean:
 * the exact pendulum quarter period is K(sin^2(theta0/2)) / sqrt(m g L / I). */
double elliptic_k(double m);

#endif
