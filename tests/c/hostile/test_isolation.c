/* Isolated FMUs through the engine's C API (also run under AddressSanitizer):
 * - in process, an FMU that logs "%s%s%n" without arguments leaves that raw text as its message;
 * - isolated, every fmi2 call the engine makes (values, states, serialization, directional
 *   derivatives) gives the in-process results bit for bit, outputs read ahead with a step
 *   included;
 * - an FMU that exits or hangs fails the call with fmi2Fatal and says why; the next instantiate
 *   starts a new host.
 *
 *     test_isolation <fmu host> <hostile.so> */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine_test_fmus.h"
#include "syssimx_engine.h"

typedef struct {
    const char *stem;
    const char *binary;
    const char *guid;
} built_fmu;

static const built_fmu built_fmus[] = {ENGINE_TEST_FMUS};

#define CHECK(condition) do { \
        if (!(condition)) { \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition); \
            exit(1); \
        } \
    } while (0)

#define CHECK_MESSAGE(fmu, expected) do { \
        const char *message_ = ssx_fmu_last_message(fmu); \
        if (strcmp(message_, expected) != 0) { \
            fprintf(stderr, "%s:%d: message \"%s\", expected \"%s\"\n", __FILE__, __LINE__, \
                    message_, expected); \
            exit(1); \
        } \
    } while (0)

enum { FMI2_OK = 0, FMI2_ERROR = 3, FMI2_FATAL = 4 };
enum { HOSTILE_Y = 0, HOSTILE_MODE = 1, HOSTILE_FAIL_TIME = 2 };
enum { BEHAVE = 0, EXIT = 3, ENDLESS_LOOP = 4, BAD_LOG_FORMAT = 5 };
enum { THETA = 0, OMEGA = 1, ALPHA = 2, TORQUE = 4, THETA0 = 7, OMEGA0 = 8 };

/* host NULL: in process. */
static ssx_fmu *load(const char *host, double step_timeout, const char *binary,
                     const char *model_identifier, const char *guid)
{
    char error[1024];
    ssx_fmu_load_spec spec = {.version = SSX_FMI2, .interface = SSX_CO_SIMULATION,
                              .binary_path = binary, .model_identifier = model_identifier,
                              .guid = guid, .resource_location = "", .instance_name = "F",
                              .host_path = host, .step_timeout = step_timeout};
    ssx_fmu *fmu = ssx_fmu_load(&spec, error, sizeof error);
    if (fmu == NULL) {
        fprintf(stderr, "cannot load %s: %s\n", binary, error);
        exit(1);
    }
    return fmu;
}

static void start_hostile(ssx_fmu *fmu, int mode)
{
    const unsigned int mode_vr = HOSTILE_MODE, fail_time_vr = HOSTILE_FAIL_TIME;
    const double fail_time = 0.45;
    const ssx_fmu_experiment experiment = {.start_time = 0.0};
    const ssx_fmu_values starts = {.real_vr = &fail_time_vr, .real_values = &fail_time,
                                   .n_real = 1, .integer_vr = &mode_vr,
                                   .integer_values = &mode, .n_integer = 1};
    CHECK(ssx_fmu_initialize(fmu, &experiment, &starts, NULL, NULL) == FMI2_OK);
}

static void test_bad_log_format_in_process(const char *hostile)
{
    ssx_fmu *fmu = load(NULL, 0.0, hostile, "hostile", "");
    start_hostile(fmu, BAD_LOG_FORMAT);
    CHECK(ssx_fmu_do_step(fmu, 0.0, 0.5, 1) == FMI2_ERROR);
    CHECK_MESSAGE(fmu, "%s%s%n");
    ssx_fmu_free(fmu);
}

static void test_exit_and_a_new_host(const char *host, const char *hostile)
{
    ssx_fmu *fmu = load(host, 0.0, hostile, "hostile", "");
    start_hostile(fmu, EXIT);
    CHECK(ssx_fmu_do_step(fmu, 0.0, 0.25, 1) == FMI2_OK);
    CHECK(ssx_fmu_do_step(fmu, 0.25, 0.25, 1) == FMI2_FATAL);
    CHECK_MESSAGE(fmu, "the FMU process exited with status 3 in fmi2DoStep");
    const unsigned int y_vr = HOSTILE_Y;
    double y = -1.0;
    /* FMI 2.0 allows no call after fmi2Fatal: refused by the binding, the host is not asked */
    CHECK(ssx_fmu_get_real(fmu, &y_vr, 1, &y) == -1);
    CHECK_MESSAGE(fmu, "fmi2GetReal refused: fmi2DoStep returned fmi2Fatal earlier, and FMI 2.0 "
                       "allows no further call on the FMU");
    start_hostile(fmu, BEHAVE);
    CHECK(ssx_fmu_do_step(fmu, 0.0, 1.0, 1) == FMI2_OK);
    CHECK(ssx_fmu_get_real(fmu, &y_vr, 1, &y) == FMI2_OK);
    CHECK(y == 1.0);
    ssx_fmu_free(fmu);
}

static void test_step_timeout(const char *host, const char *hostile)
{
    ssx_fmu *fmu = load(host, 0.2, hostile, "hostile", "");
    start_hostile(fmu, ENDLESS_LOOP);
    CHECK(ssx_fmu_do_step(fmu, 0.0, 1.0, 1) == FMI2_FATAL);
    CHECK_MESSAGE(fmu, "fmi2DoStep did not return within the step timeout of 0.2 s: the FMU "
                       "process was killed");
    ssx_fmu_free(fmu);
}

/* Every kind of call the engine makes, recorded into out; returns the count of values. */
static size_t exercise(ssx_fmu *fmu, double *out)
{
    size_t n = 0;
    const unsigned int starts_vr[] = {THETA0, OMEGA0};
    const double starts[] = {0.5, 0.1};
    const unsigned int outputs_vr[] = {THETA, OMEGA, ALPHA};
    const unsigned int torque_vr = TORQUE;
    const ssx_fmu_experiment experiment = {.start_time = 0.0, .tolerance_defined = 1,
                                           .tolerance = 1e-8};
    const ssx_fmu_values start_values = {.real_vr = starts_vr, .real_values = starts,
                                         .n_real = 2};
    CHECK(ssx_fmu_initialize(fmu, &experiment, &start_values, NULL, NULL) == FMI2_OK);
    CHECK(ssx_fmu_do_step(fmu, 0.0, 0.1, 0) == FMI2_OK);
    void *state = NULL;
    CHECK(ssx_fmu_get_state(fmu, &state) == FMI2_OK && state != NULL);
    const double torque = 0.3;
    CHECK(ssx_fmu_set_real(fmu, &torque_vr, 1, &torque) == FMI2_OK);
    CHECK(ssx_fmu_do_step(fmu, 0.1, 0.1, 0) == FMI2_OK);
    CHECK(ssx_fmu_get_real(fmu, outputs_vr, 3, out + n) == FMI2_OK);
    n += 3;
    CHECK(ssx_fmu_set_state(fmu, state) == FMI2_OK);
    CHECK(ssx_fmu_do_step(fmu, 0.1, 0.05, 0) == FMI2_OK);
    CHECK(ssx_fmu_get_real(fmu, outputs_vr, 3, out + n) == FMI2_OK);
    n += 3;
    /* isolated, the step reads the outputs ahead; the restore in between must discard them */
    CHECK(ssx_fmu_do_step(fmu, 0.15, 0.05, 0) == FMI2_OK);
    CHECK(ssx_fmu_set_state(fmu, state) == FMI2_OK);
    CHECK(ssx_fmu_get_real(fmu, outputs_vr, 3, out + n) == FMI2_OK);
    CHECK(out[n] != out[n - 3]);
    n += 3;
    size_t size = 0;
    CHECK(ssx_fmu_serialized_state_size(fmu, state, &size) == FMI2_OK && size > 0);
    char *bytes = malloc(size);
    CHECK(bytes != NULL);
    CHECK(ssx_fmu_serialize_state(fmu, state, bytes, size) == FMI2_OK);
    void *copy = NULL;
    CHECK(ssx_fmu_deserialize_state(fmu, bytes, size, &copy) == FMI2_OK && copy != NULL);
    free(bytes);
    CHECK(ssx_fmu_do_step(fmu, 0.1, 0.05, 0) == FMI2_OK);
    CHECK(ssx_fmu_get_state(fmu, &state) == FMI2_OK); /* reused: now at t = 0.15 */
    CHECK(ssx_fmu_set_state(fmu, copy) == FMI2_OK);   /* back to t = 0.1 */
    CHECK(ssx_fmu_do_step(fmu, 0.1, 0.2, 0) == FMI2_OK);
    CHECK(ssx_fmu_get_real(fmu, outputs_vr, 3, out + n) == FMI2_OK);
    n += 3;
    const unsigned int alpha_vr = ALPHA;
    const double seed = 1.0;
    CHECK(ssx_fmu_get_directional_derivative(fmu, &alpha_vr, 1, &torque_vr, 1, &seed,
                                             out + n) == FMI2_OK);
    n += 1;
    CHECK(ssx_fmu_free_state(fmu, &copy) == FMI2_OK && copy == NULL);
    CHECK(ssx_fmu_terminate(fmu) == FMI2_OK);
    CHECK(ssx_fmu_free_instance(fmu) == FMI2_OK); /* frees `state` with the instance */
    return n;
}

static void test_same_results_isolated(const char *host)
{
    const built_fmu *pendulum = NULL;
    for (size_t i = 0; i < sizeof built_fmus / sizeof built_fmus[0]; ++i) {
        if (strcmp(built_fmus[i].stem, "pendulum_cvode") == 0) {
            pendulum = &built_fmus[i];
        }
    }
    CHECK(pendulum != NULL);
    double here[16], there[16];
    ssx_fmu *local = load(NULL, 0.0, pendulum->binary, pendulum->stem, pendulum->guid);
    size_t n = exercise(local, here);
    ssx_fmu_free(local);
    ssx_fmu *isolated = load(host, 5.0, pendulum->binary, pendulum->stem, pendulum->guid);
    CHECK(exercise(isolated, there) == n);
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(isolated, &counters);
    CHECK(counters.do_step == 6 && counters.get_state == 2 && counters.set_state == 3);
    ssx_fmu_free(isolated);
    CHECK(memcmp(here, there, n * sizeof *here) == 0);
    CHECK(here[n - 1] != 0.0); /* the derivative really came back */
}

static void test_missing_binary(const char *host)
{
    char error[1024];
    ssx_fmu_load_spec spec = {.version = SSX_FMI2, .interface = SSX_CO_SIMULATION,
                              .binary_path = "/nonexistent/missing.so",
                              .model_identifier = "missing", .guid = "",
                              .resource_location = "", .instance_name = "F", .host_path = host};
    CHECK(ssx_fmu_load(&spec, error, sizeof error) == NULL);
    CHECK(strncmp(error, "cannot load the FMU binary /nonexistent/missing.so: ", 52) == 0);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s <fmu host> <hostile.so>\n", argv[0]);
        return 2;
    }
    test_bad_log_format_in_process(argv[2]);
    test_exit_and_a_new_host(argv[1], argv[2]);
    test_step_timeout(argv[1], argv[2]);
    test_same_results_isolated(argv[1]);
    test_missing_binary(argv[1]);
    return 0;
}
