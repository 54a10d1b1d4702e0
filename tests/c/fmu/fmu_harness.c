#include "fmu_harness.h"

#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void check_that(int condition, const char *text, const char *file, int line)
{
    if (condition)
        return;
    fprintf(stderr, "%s:%d: check failed: %s\n", file, line, text);
    exit(1);
}

void check_near(const char *label, double actual, double expected, double tolerance,
                const char *file, int line)
{
    double difference = fabs(actual - expected);
    printf("%-48s %.17g (expected %.17g, |diff| %.3g <= %.3g)\n", label, actual, expected,
           difference, tolerance);
    if (!(difference <= tolerance)) {
        fprintf(stderr, "%s:%d: %s is off by %.3g\n", file, line, label, difference);
        exit(1);
    }
}

static void record_message(fmi2ComponentEnvironment environment, fmi2String instance_name,
                           fmi2Status status, fmi2String category, fmi2String message, ...)
{
    (void)instance_name;
    log_record *log = environment;
    log->count++;
    log->last_status = status;
    snprintf(log->last_category, sizeof log->last_category, "%s", category ? category : "");
    snprintf(log->last_message, sizeof log->last_message, "%s", message ? message : "");
}

static char *read_text(const char *path)
{
    FILE *file = fopen(path, "rb");
    if (file == NULL)
        return NULL;
    fseek(file, 0, SEEK_END);
    long size = ftell(file);
    fseek(file, 0, SEEK_SET);
    char *text = malloc((size_t)size + 1);
    if (text != NULL && fread(text, 1, (size_t)size, file) != (size_t)size) {
        free(text);
        text = NULL;
    }
    if (text != NULL)
        text[size] = '\0';
    fclose(file);
    return text;
}

static void *resolve(test_fmu *fmu, const char *name)
{
    void *symbol = dlsym(fmu->library, name);
    if (symbol == NULL) {
        fprintf(stderr, "the FMU does not export %s\n", name);
        exit(1);
    }
    return symbol;
}

void fmu_open(test_fmu *fmu, const char *binary_path, const char *description_path)
{
    memset(fmu, 0, sizeof *fmu);
    fmu->library = dlopen(binary_path, RTLD_NOW | RTLD_LOCAL);
    if (fmu->library == NULL) {
        fprintf(stderr, "cannot load %s: %s\n", binary_path, dlerror());
        exit(1);
    }
    fmu->description = read_text(description_path);
    CHECK(fmu->description != NULL);
    const char *guid = strstr(fmu->description, "guid=\"");
    CHECK(guid != NULL);
    guid += strlen("guid=\"");
    size_t length = strcspn(guid, "\"");
    CHECK(length < sizeof fmu->guid);
    memcpy(fmu->guid, guid, length);
    fmu->guid[length] = '\0';
    fmu->callbacks = (fmi2CallbackFunctions){record_message, calloc, free, NULL, &fmu->log};
    /* object pointers to function pointers via memcpy: ISO C has no direct conversion */
#define RESOLVE(field, name)                                  \
    do {                                                      \
        void *symbol = resolve(fmu, name);                    \
        memcpy(&fmu->field, &symbol, sizeof fmu->field);      \
    } while (0)
    RESOLVE(instantiate, "fmi2Instantiate");
    RESOLVE(free_instance, "fmi2FreeInstance");
    RESOLVE(set_debug_logging, "fmi2SetDebugLogging");
    RESOLVE(setup_experiment, "fmi2SetupExperiment");
    RESOLVE(enter_initialization_mode, "fmi2EnterInitializationMode");
    RESOLVE(exit_initialization_mode, "fmi2ExitInitializationMode");
    RESOLVE(terminate, "fmi2Terminate");
    RESOLVE(reset, "fmi2Reset");
    RESOLVE(get_real, "fmi2GetReal");
    RESOLVE(set_real, "fmi2SetReal");
    RESOLVE(get_integer, "fmi2GetInteger");
    RESOLVE(set_integer, "fmi2SetInteger");
    RESOLVE(get_boolean, "fmi2GetBoolean");
    RESOLVE(do_step, "fmi2DoStep");
    RESOLVE(get_state, "fmi2GetFMUstate");
    RESOLVE(set_state, "fmi2SetFMUstate");
    RESOLVE(free_state, "fmi2FreeFMUstate");
    RESOLVE(serialized_size, "fmi2SerializedFMUstateSize");
    RESOLVE(serialize, "fmi2SerializeFMUstate");
    RESOLVE(deserialize, "fmi2DeSerializeFMUstate");
    RESOLVE(get_derivatives, "fmi2GetDerivatives");
    RESOLVE(set_time, "fmi2SetTime");
    RESOLVE(set_continuous_states, "fmi2SetContinuousStates");
    RESOLVE(get_continuous_states, "fmi2GetContinuousStates");
    RESOLVE(get_event_indicators, "fmi2GetEventIndicators");
    RESOLVE(enter_event_mode, "fmi2EnterEventMode");
    RESOLVE(new_discrete_states, "fmi2NewDiscreteStates");
    RESOLVE(enter_continuous_time_mode, "fmi2EnterContinuousTimeMode");
#undef RESOLVE
}

void fmu_close(test_fmu *fmu)
{
    free(fmu->description);
    if (fmu->library != NULL)
        dlclose(fmu->library);
    memset(fmu, 0, sizeof *fmu);
}

fmi2ValueReference fmu_vr(const test_fmu *fmu, const char *name)
{
    char pattern[128];
    snprintf(pattern, sizeof pattern, "name=\"%s\" valueReference=\"", name);
    const char *found = strstr(fmu->description, pattern);
    if (found == NULL) {
        fprintf(stderr, "the FMU has no variable %s\n", name);
        exit(1);
    }
    return (fmi2ValueReference)strtoul(found + strlen(pattern), NULL, 10);
}

fmi2Component fmu_start(test_fmu *fmu, double tolerance, double t0, const char *const names[],
                        const double values[], size_t n)
{
    fmi2Component c = fmu->instantiate("test", fmi2CoSimulation, fmu->guid, "", &fmu->callbacks,
                                       fmi2False, fmi2True);
    CHECK(c != NULL);
    CHECK_OK(fmu->setup_experiment(c, tolerance > 0, tolerance, t0, fmi2False, 0.0));
    CHECK_OK(fmu->enter_initialization_mode(c));
    for (size_t i = 0; i < n; ++i)
        fmu_set(fmu, c, names[i], values[i]);
    CHECK_OK(fmu->exit_initialization_mode(c));
    return c;
}

double fmu_get(test_fmu *fmu, fmi2Component c, const char *name)
{
    fmi2ValueReference vr = fmu_vr(fmu, name);
    double value = NAN;
    CHECK_OK(fmu->get_real(c, &vr, 1, &value));
    return value;
}

void fmu_set(test_fmu *fmu, fmi2Component c, const char *name, double value)
{
    fmi2ValueReference vr = fmu_vr(fmu, name);
    CHECK_OK(fmu->set_real(c, &vr, 1, &value));
}

double fmu_find_time(test_fmu *fmu, fmi2Component c, double t_from, double dt, double t_max,
                     const char *name, value_predicate predicate, double resolution,
                     double *t_now)
{
    fmi2FMUstate saved = NULL;
    for (long k = 0;; ++k) {
        double t = t_from + (double)k * dt;
        CHECK(t < t_max);
        CHECK_OK(fmu->get_state(c, &saved));
        CHECK_OK(fmu->do_step(c, t, dt, fmi2False));
        if (!predicate(fmu_get(fmu, c, name)))
            continue;
        double low = 0.0, high = dt;
        while (high - low > resolution) {
            double middle = 0.5 * (low + high);
            CHECK_OK(fmu->set_state(c, saved));
            CHECK_OK(fmu->do_step(c, t, middle, fmi2False));
            if (predicate(fmu_get(fmu, c, name)))
                high = middle;
            else
                low = middle;
        }
        CHECK_OK(fmu->set_state(c, saved));
        CHECK_OK(fmu->do_step(c, t, high, fmi2False));
        CHECK_OK(fmu->free_state(c, &saved));
        *t_now = t + high;
        return t + 0.5 * (low + high);
    }
}

double elliptic_k(double m)
{
    double a = 1.0, b = sqrt(1.0 - m);
    /* converges quadratically; a few ulps is as close as a and b get */
    for (int i = 0; i < 64 && fabs(a - b) > 4e-16 * a; ++i) {
        double mean = 0.5 * (a + b);
        b = sqrt(a * b);
        a = mean;
    }
    return acos(-1.0) / (2.0 * a);
}
