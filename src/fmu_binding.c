/* The FMU binding: one dlopen'ed FMI 2.0 Co-Simulation binary, its function table and at most
 * one live instance, with counters of every fmi2 call and the last message the FMU logged. */
#define _POSIX_C_SOURCE 200809L

#include "fmu_binding.h"

#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "array.h"
#include "fmi2Functions.h"
#include "fmu_message.h"
#include "fmu_remote.h"

typedef struct {
    fmi2InstantiateTYPE *instantiate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2SetupExperimentTYPE *setup_experiment;
    fmi2EnterInitializationModeTYPE *enter_initialization_mode;
    fmi2ExitInitializationModeTYPE *exit_initialization_mode;
    fmi2TerminateTYPE *terminate;
    fmi2ResetTYPE *reset;
    fmi2GetRealTYPE *get_real;
    fmi2GetIntegerTYPE *get_integer;
    fmi2GetBooleanTYPE *get_boolean;
    fmi2SetRealTYPE *set_real;
    fmi2SetIntegerTYPE *set_integer;
    fmi2SetBooleanTYPE *set_boolean;
    fmi2DoStepTYPE *do_step;
    /* optional: absent in FMUs without the capability */
    fmi2GetFMUstateTYPE *get_state;
    fmi2SetFMUstateTYPE *set_state;
    fmi2FreeFMUstateTYPE *free_state;
    fmi2SerializedFMUstateSizeTYPE *serialized_state_size;
    fmi2SerializeFMUstateTYPE *serialize_state;
    fmi2DeSerializeFMUstateTYPE *deserialize_state;
    fmi2GetDirectionalDerivativeTYPE *get_directional_derivative;
    fmi2GetBooleanStatusTYPE *get_boolean_status;
    fmi2GetRealStatusTYPE *get_real_status;
} fmi2_table;

struct ssx_fmu {
    void *library;
    ssx_remote *remote; /* an isolated FMU's host process; NULL when the binary runs here */
    fmi2_table fn;
    char *model_identifier;
    char *guid;
    char *resource_uri;
    char *instance_name;
    int logging_on;
    fmi2CallbackFunctions callbacks; /* must outlive the instance: the FMU keeps the pointer */
    fmi2Component instance;
    const char *current_call; /* the fmi2 function being called, named by live() */
    /* the call that returned fmi2Fatal, or NULL: after it FMI 2.0 allows no call at all, not
     * even fmi2FreeInstance, so the instance and its states are abandoned (instance NULL) and
     * the library stays loaded */
    const char *fatal_call;
    long generation;
    long values_epoch; /* see ssx_fmu_values_epoch */
    /* FMU states handed out by the live instance, freed with it */
    void **states;
    size_t n_states;
    size_t states_capacity;
    ssx_fmu_counters counters;
    char last_message[1024];
};

static const char *const status_names[] = {"fmi2OK",    "fmi2Warning", "fmi2Discard",
                                           "fmi2Error", "fmi2Fatal",   "fmi2Pending"};

const char *ssx_fmi2_status_name(int status)
{
    if (status >= 0 && status < (int)(sizeof status_names / sizeof status_names[0])) {
        return status_names[status];
    }
    return "no fmi2 status (the engine failed)";
}

static void logger(fmi2ComponentEnvironment environment, fmi2String instance_name,
                   fmi2Status status, fmi2String category, fmi2String message, ...)
{
    (void)instance_name;
    (void)status;
    (void)category;
    ssx_fmu *fmu = environment;
    if (fmu == NULL || message == NULL) {
        return;
    }
    va_list args;
    va_start(args, message);
    ssx_format_fmu_message(fmu->last_message, sizeof fmu->last_message, message, args);
    va_end(args);
}

static void note(ssx_fmu *fmu, const char *text)
{
    snprintf(fmu->last_message, sizeof fmu->last_message, "%s", text);
}

static char *duplicate(const char *text)
{
    return strdup(text != NULL ? text : "");
}

/* Unprefixed names first; FMUs compiled with FMI2_FUNCTION_PREFIX export <id>_fmi2Name. */
static void *resolve(void *library, const char *model_identifier, const char *name)
{
    void *symbol = dlsym(library, name);
    if (symbol == NULL && model_identifier[0] != '\0') {
        char prefixed[256];
        snprintf(prefixed, sizeof prefixed, "%s_%s", model_identifier, name);
        symbol = dlsym(library, prefixed);
    }
    return symbol;
}

/* dlsym returns void *; C11 has no direct cast to a function pointer, hence the memcpy. An
 * isolated FMU's functions forward each call to its host process. */
#define RESOLVE(field, name) do { \
        void *symbol_ = remote != NULL ? ssx_remote_function(remote, name) \
                                       : resolve(library, model_identifier, name); \
        memcpy(&fmu->fn.field, &symbol_, sizeof symbol_); \
    } while (0)

static void unload(void *library, ssx_remote *remote)
{
    if (remote != NULL) {
        ssx_remote_stop(remote);
    } else {
        dlclose(library);
    }
}

/* host_path NULL: dlopen the binary into this process; otherwise run it in a host process. */
static ssx_fmu *load(const char *host_path, double step_timeout, const char *binary_path,
                     const char *model_identifier, const char *guid, const char *resource_uri,
                     const char *instance_name, int logging_on, char *error, size_t error_size)
{
    if (binary_path == NULL || model_identifier == NULL) {
        snprintf(error, error_size, "ssx_fmu_load: binary path and model identifier are required");
        return NULL;
    }
    void *library = NULL;
    ssx_remote *remote = NULL;
    if (host_path != NULL) {
        remote = ssx_remote_start(host_path, binary_path, model_identifier, step_timeout, error,
                                  error_size);
        if (remote == NULL) {
            return NULL;
        }
    } else {
        library = dlopen(binary_path, RTLD_NOW | RTLD_LOCAL);
        if (library == NULL) {
            const char *reason = dlerror();
            snprintf(error, error_size, "cannot load the FMU binary %s: %s", binary_path,
                     reason != NULL ? reason : "unknown dlopen failure");
            return NULL;
        }
    }
    ssx_fmu *fmu = calloc(1, sizeof *fmu);
    if (fmu == NULL) {
        unload(library, remote);
        snprintf(error, error_size, "out of memory loading %s", binary_path);
        return NULL;
    }
    fmu->library = library;
    fmu->remote = remote;
    RESOLVE(instantiate, "fmi2Instantiate");
    RESOLVE(free_instance, "fmi2FreeInstance");
    RESOLVE(setup_experiment, "fmi2SetupExperiment");
    RESOLVE(enter_initialization_mode, "fmi2EnterInitializationMode");
    RESOLVE(exit_initialization_mode, "fmi2ExitInitializationMode");
    RESOLVE(terminate, "fmi2Terminate");
    RESOLVE(reset, "fmi2Reset");
    RESOLVE(get_real, "fmi2GetReal");
    RESOLVE(get_integer, "fmi2GetInteger");
    RESOLVE(get_boolean, "fmi2GetBoolean");
    RESOLVE(set_real, "fmi2SetReal");
    RESOLVE(set_integer, "fmi2SetInteger");
    RESOLVE(set_boolean, "fmi2SetBoolean");
    RESOLVE(do_step, "fmi2DoStep");
    RESOLVE(get_state, "fmi2GetFMUstate");
    RESOLVE(set_state, "fmi2SetFMUstate");
    RESOLVE(free_state, "fmi2FreeFMUstate");
    RESOLVE(serialized_state_size, "fmi2SerializedFMUstateSize");
    RESOLVE(serialize_state, "fmi2SerializeFMUstate");
    RESOLVE(deserialize_state, "fmi2DeSerializeFMUstate");
    RESOLVE(get_directional_derivative, "fmi2GetDirectionalDerivative");
    RESOLVE(get_boolean_status, "fmi2GetBooleanStatus");
    RESOLVE(get_real_status, "fmi2GetRealStatus");

    const struct {
        const char *name;
        int present;
    } required[] = {
        {"fmi2Instantiate", fmu->fn.instantiate != NULL},
        {"fmi2FreeInstance", fmu->fn.free_instance != NULL},
        {"fmi2SetupExperiment", fmu->fn.setup_experiment != NULL},
        {"fmi2EnterInitializationMode", fmu->fn.enter_initialization_mode != NULL},
        {"fmi2ExitInitializationMode", fmu->fn.exit_initialization_mode != NULL},
        {"fmi2Terminate", fmu->fn.terminate != NULL},
        {"fmi2Reset", fmu->fn.reset != NULL},
        {"fmi2GetReal", fmu->fn.get_real != NULL},
        {"fmi2GetInteger", fmu->fn.get_integer != NULL},
        {"fmi2GetBoolean", fmu->fn.get_boolean != NULL},
        {"fmi2SetReal", fmu->fn.set_real != NULL},
        {"fmi2SetInteger", fmu->fn.set_integer != NULL},
        {"fmi2SetBoolean", fmu->fn.set_boolean != NULL},
        {"fmi2DoStep", fmu->fn.do_step != NULL},
    };
    for (size_t i = 0; i < sizeof required / sizeof required[0]; ++i) {
        if (!required[i].present) {
            snprintf(error, error_size,
                     "%s does not export %s: not an FMI 2.0 Co-Simulation binary", binary_path,
                     required[i].name);
            unload(library, remote);
            free(fmu);
            return NULL;
        }
    }
    fmu->model_identifier = duplicate(model_identifier);
    fmu->guid = duplicate(guid);
    fmu->resource_uri = duplicate(resource_uri);
    fmu->instance_name = duplicate(instance_name != NULL ? instance_name : model_identifier);
    if (fmu->model_identifier == NULL || fmu->guid == NULL || fmu->resource_uri == NULL ||
        fmu->instance_name == NULL) {
        snprintf(error, error_size, "out of memory loading %s", binary_path);
        ssx_fmu_free(fmu);
        return NULL;
    }
    fmu->logging_on = logging_on;
    fmu->callbacks.logger = logger;
    fmu->callbacks.allocateMemory = calloc;
    fmu->callbacks.freeMemory = free;
    fmu->callbacks.stepFinished = NULL;
    fmu->callbacks.componentEnvironment = fmu;
    return fmu;
}

ssx_fmu *ssx_fmu_load(const char *binary_path, const char *model_identifier, const char *guid,
                      const char *resource_uri, const char *instance_name, int logging_on,
                      char *error, size_t error_size)
{
    return load(NULL, 0.0, binary_path, model_identifier, guid, resource_uri, instance_name,
                logging_on, error, error_size);
}

ssx_fmu *ssx_fmu_load_isolated(const char *host_path, double step_timeout,
                               const char *binary_path, const char *model_identifier,
                               const char *guid, const char *resource_uri,
                               const char *instance_name, int logging_on, char *error,
                               size_t error_size)
{
    if (host_path == NULL) {
        snprintf(error, error_size, "ssx_fmu_load_isolated: the FMU host's path is required");
        return NULL;
    }
    return load(host_path, step_timeout, binary_path, model_identifier, guid, resource_uri,
                instance_name, logging_on, error, error_size);
}

/* Every call on the instance goes through here first. */
static int live(ssx_fmu *fmu, const char *function)
{
    if (fmu == NULL) {
        return 0;
    }
    if (fmu->instance == NULL) {
        if (fmu->fatal_call != NULL) {
            snprintf(fmu->last_message, sizeof fmu->last_message,
                     "%s refused: %s returned fmi2Fatal earlier, and FMI 2.0 allows no further "
                     "call on the FMU",
                     function, fmu->fatal_call);
        } else {
            snprintf(fmu->last_message, sizeof fmu->last_message,
                     "%s called without a live instance (call instantiate first)", function);
        }
        return 0;
    }
    fmu->current_call = function;
    return 1;
}

/* Every status an instance returns comes back through here: a fatal one ends all calls. */
static int outcome(ssx_fmu *fmu, fmi2Status status)
{
    if (status == fmi2Fatal) {
        fmu->fatal_call = fmu->current_call;
        fmu->instance = NULL;
        fmu->n_states = 0;
    }
    return (int)status;
}

static int forget_state(ssx_fmu *fmu, void *state)
{
    for (size_t i = 0; i < fmu->n_states; ++i) {
        if (fmu->states[i] == state) {
            fmu->states[i] = fmu->states[--fmu->n_states];
            return 0;
        }
    }
    return -1;
}

static int knows_state(const ssx_fmu *fmu, const void *state)
{
    for (size_t i = 0; i < fmu->n_states; ++i) {
        if (fmu->states[i] == state) {
            return 1;
        }
    }
    return 0;
}

static int remember_state(ssx_fmu *fmu, void *state)
{
    if (array_reserve((void **)&fmu->states, &fmu->states_capacity, fmu->n_states + 1,
                      sizeof *fmu->states, 4) != 0) {
        return -1;
    }
    fmu->states[fmu->n_states++] = state;
    return 0;
}

int ssx_fmu_free_instance(ssx_fmu *fmu)
{
    if (fmu == NULL) {
        return -1;
    }
    int worst = fmi2OK;
    if (fmu->instance != NULL) {
        /* States belong to their instance: release them while it still exists. */
        while (fmu->n_states > 0) {
            fmi2FMUstate state = fmu->states[--fmu->n_states];
            if (fmu->fn.free_state != NULL) {
                int status = (int)fmu->fn.free_state(fmu->instance, &state);
                worst = status > worst ? status : worst;
            }
        }
        fmu->fn.free_instance(fmu->instance);
        fmu->instance = NULL;
    }
    return worst; /* the worst fmi2FreeFMUstate status; the instance is gone either way */
}

void ssx_fmu_free(ssx_fmu *fmu)
{
    if (fmu == NULL) {
        return;
    }
    if (fmu->instance != NULL) {
        /* Teardown goes on whatever the FMU answers: there is no one left to report to. */
        (void)fmu->fn.terminate(fmu->instance);
    }
    (void)ssx_fmu_free_instance(fmu);
    free(fmu->states);
    free(fmu->model_identifier);
    free(fmu->guid);
    free(fmu->resource_uri);
    free(fmu->instance_name);
    /* unloading would run the code of a library that declared itself broken; a host process
     * can always be ended */
    if (fmu->fatal_call == NULL || fmu->remote != NULL) {
        unload(fmu->library, fmu->remote);
    }
    free(fmu);
}

int ssx_fmu_instantiate(ssx_fmu *fmu)
{
    if (fmu == NULL) {
        return -1;
    }
    if (fmu->fatal_call != NULL && fmu->remote == NULL) {
        (void)live(fmu, "fmi2Instantiate"); /* says why */
        return -1;
    }
    if (fmu->fatal_call != NULL) {
        /* an isolated FMU starts over in a new host: the broken one is ended, never called */
        ssx_remote_restart(fmu->remote);
        fmu->fatal_call = NULL;
    }
    /* a state the old instance fails to free is its leak, not a reason to refuse a new one */
    (void)ssx_fmu_free_instance(fmu);
    fmu->last_message[0] = '\0';
    fmu->counters.instantiate++;
    fmu->instance = fmu->fn.instantiate(fmu->instance_name, fmi2CoSimulation, fmu->guid,
                                        fmu->resource_uri, &fmu->callbacks, fmi2False,
                                        fmu->logging_on ? fmi2True : fmi2False);
    fmu->generation++;
    fmu->values_epoch++;
    if (fmu->instance == NULL) {
        if (fmu->last_message[0] == '\0') {
            note(fmu, "fmi2Instantiate returned NULL");
        }
        return -1;
    }
    return 0;
}

int ssx_fmu_setup_experiment(ssx_fmu *fmu, int tolerance_defined, double tolerance,
                             double start_time, int stop_time_defined, double stop_time)
{
    if (!live(fmu, "fmi2SetupExperiment")) {
        return -1;
    }
    return outcome(fmu, fmu->fn.setup_experiment(
                            fmu->instance, tolerance_defined ? fmi2True : fmi2False, tolerance,
                            start_time, stop_time_defined ? fmi2True : fmi2False, stop_time));
}

int ssx_fmu_enter_initialization_mode(ssx_fmu *fmu)
{
    if (!live(fmu, "fmi2EnterInitializationMode")) {
        return -1;
    }
    return outcome(fmu, fmu->fn.enter_initialization_mode(fmu->instance));
}

int ssx_fmu_exit_initialization_mode(ssx_fmu *fmu)
{
    if (!live(fmu, "fmi2ExitInitializationMode")) {
        return -1;
    }
    return outcome(fmu, fmu->fn.exit_initialization_mode(fmu->instance));
}

int ssx_fmu_do_step(ssx_fmu *fmu, double t, double h, int no_set_fmu_state_prior)
{
    if (!live(fmu, "fmi2DoStep")) {
        return -1;
    }
    fmu->counters.do_step++;
    return outcome(fmu, fmu->fn.do_step(fmu->instance, t, h,
                                        no_set_fmu_state_prior ? fmi2True : fmi2False));
}

int ssx_fmu_get_real(ssx_fmu *fmu, const unsigned int *vr, size_t n, double *values)
{
    if (!live(fmu, "fmi2GetReal")) {
        return -1;
    }
    fmu->counters.get_values++;
    return outcome(fmu, fmu->fn.get_real(fmu->instance, vr, n, values));
}

int ssx_fmu_set_real(ssx_fmu *fmu, const unsigned int *vr, size_t n, const double *values)
{
    if (!live(fmu, "fmi2SetReal")) {
        return -1;
    }
    fmu->counters.set_values++;
    fmu->values_epoch++;
    return outcome(fmu, fmu->fn.set_real(fmu->instance, vr, n, values));
}

int ssx_fmu_get_integer(ssx_fmu *fmu, const unsigned int *vr, size_t n, int *values)
{
    if (!live(fmu, "fmi2GetInteger")) {
        return -1;
    }
    fmu->counters.get_values++;
    return outcome(fmu, fmu->fn.get_integer(fmu->instance, vr, n, values));
}

int ssx_fmu_set_integer(ssx_fmu *fmu, const unsigned int *vr, size_t n, const int *values)
{
    if (!live(fmu, "fmi2SetInteger")) {
        return -1;
    }
    fmu->counters.set_values++;
    fmu->values_epoch++;
    return outcome(fmu, fmu->fn.set_integer(fmu->instance, vr, n, values));
}

int ssx_fmu_get_boolean(ssx_fmu *fmu, const unsigned int *vr, size_t n, int *values)
{
    if (!live(fmu, "fmi2GetBoolean")) {
        return -1;
    }
    fmu->counters.get_values++;
    return outcome(fmu, fmu->fn.get_boolean(fmu->instance, vr, n, values));
}

int ssx_fmu_set_boolean(ssx_fmu *fmu, const unsigned int *vr, size_t n, const int *values)
{
    if (!live(fmu, "fmi2SetBoolean")) {
        return -1;
    }
    fmu->counters.set_values++;
    fmu->values_epoch++;
    return outcome(fmu, fmu->fn.set_boolean(fmu->instance, vr, n, values));
}

int ssx_fmu_get_state(ssx_fmu *fmu, void **state)
{
    if (state == NULL || !live(fmu, "fmi2GetFMUstate")) {
        return -1;
    }
    if (fmu->fn.get_state == NULL) {
        note(fmu, "this FMU does not provide fmi2GetFMUstate");
        return -1;
    }
    if (*state != NULL && !knows_state(fmu, *state)) {
        note(fmu, "fmi2GetFMUstate: the state to reuse does not belong to the live instance");
        return -1;
    }
    int fresh = *state == NULL;
    fmu->counters.get_state++;
    int status = outcome(fmu, fmu->fn.get_state(fmu->instance, state));
    if (fresh && *state != NULL && remember_state(fmu, *state) != 0) {
        if (fmu->fn.free_state != NULL) {
            fmu->fn.free_state(fmu->instance, state);
        }
        note(fmu, "out of memory tracking FMU states");
        return -1;
    }
    return status;
}

int ssx_fmu_set_state(ssx_fmu *fmu, void *state)
{
    if (fmu == NULL || !live(fmu, "fmi2SetFMUstate")) {
        return -1;
    }
    if (fmu->fn.set_state == NULL) {
        note(fmu, "this FMU does not provide fmi2SetFMUstate");
        return -1;
    }
    if (!knows_state(fmu, state)) {
        note(fmu, "fmi2SetFMUstate: the state does not belong to the live instance");
        return -1;
    }
    fmu->counters.set_state++;
    fmu->values_epoch++;
    return outcome(fmu, fmu->fn.set_state(fmu->instance, state));
}

int ssx_fmu_free_state(ssx_fmu *fmu, void **state)
{
    if (fmu == NULL || state == NULL) {
        return -1;
    }
    if (*state == NULL) {
        return 0;
    }
    /* A state of an earlier instance was already released with it (one of an instance
     * abandoned after fmi2Fatal may not be released at all). */
    if (forget_state(fmu, *state) != 0) {
        *state = NULL;
        return 0;
    }
    if (!live(fmu, "fmi2FreeFMUstate") || fmu->fn.free_state == NULL) {
        return -1;
    }
    return outcome(fmu, fmu->fn.free_state(fmu->instance, state));
}

int ssx_fmu_serialized_state_size(ssx_fmu *fmu, void *state, size_t *size)
{
    if (fmu == NULL || !live(fmu, "fmi2SerializedFMUstateSize")) {
        return -1;
    }
    if (fmu->fn.serialized_state_size == NULL) {
        note(fmu, "this FMU does not provide fmi2SerializedFMUstateSize");
        return -1;
    }
    return outcome(fmu, fmu->fn.serialized_state_size(fmu->instance, state, size));
}

int ssx_fmu_serialize_state(ssx_fmu *fmu, void *state, char *bytes, size_t size)
{
    if (fmu == NULL || !live(fmu, "fmi2SerializeFMUstate")) {
        return -1;
    }
    if (fmu->fn.serialize_state == NULL) {
        note(fmu, "this FMU does not provide fmi2SerializeFMUstate");
        return -1;
    }
    return outcome(fmu, fmu->fn.serialize_state(fmu->instance, state, bytes, size));
}

int ssx_fmu_deserialize_state(ssx_fmu *fmu, const char *bytes, size_t size, void **state)
{
    if (fmu == NULL || state == NULL || !live(fmu, "fmi2DeSerializeFMUstate")) {
        return -1;
    }
    if (fmu->fn.deserialize_state == NULL) {
        note(fmu, "this FMU does not provide fmi2DeSerializeFMUstate");
        return -1;
    }
    if (*state != NULL && !knows_state(fmu, *state)) {
        note(fmu, "fmi2DeSerializeFMUstate: the state to reuse does not belong to the live "
                  "instance");
        return -1;
    }
    int fresh = *state == NULL;
    int status = outcome(fmu, fmu->fn.deserialize_state(fmu->instance, bytes, size, state));
    if (fresh && *state != NULL && remember_state(fmu, *state) != 0) {
        note(fmu, "out of memory tracking FMU states");
        return -1;
    }
    return status;
}

int ssx_fmu_get_directional_derivative(ssx_fmu *fmu, const unsigned int *unknowns,
                                       size_t n_unknowns, const unsigned int *knowns,
                                       size_t n_knowns, const double *dv_known,
                                       double *dv_unknown)
{
    if (fmu == NULL || !live(fmu, "fmi2GetDirectionalDerivative")) {
        return -1;
    }
    if (fmu->fn.get_directional_derivative == NULL) {
        note(fmu, "this FMU does not provide fmi2GetDirectionalDerivative");
        return -1;
    }
    fmu->counters.directional_derivative++;
    return outcome(fmu, fmu->fn.get_directional_derivative(fmu->instance, unknowns, n_unknowns,
                                                           knowns, n_knowns, dv_known,
                                                           dv_unknown));
}

int ssx_fmu_reset(ssx_fmu *fmu)
{
    if (!live(fmu, "fmi2Reset")) {
        return -1;
    }
    fmu->values_epoch++;
    return outcome(fmu, fmu->fn.reset(fmu->instance));
}

int ssx_fmu_terminate(ssx_fmu *fmu)
{
    if (!live(fmu, "fmi2Terminate")) {
        return -1;
    }
    return outcome(fmu, fmu->fn.terminate(fmu->instance));
}

int ssx_fmu_get_terminated(ssx_fmu *fmu, int *terminated)
{
    if (terminated == NULL || !live(fmu, "fmi2GetBooleanStatus")) {
        return -1;
    }
    if (fmu->fn.get_boolean_status == NULL) {
        note(fmu, "this FMU does not provide fmi2GetBooleanStatus");
        return -1;
    }
    fmi2Boolean value = fmi2False;
    int status = outcome(fmu, fmu->fn.get_boolean_status(fmu->instance, fmi2Terminated, &value));
    *terminated = value != fmi2False;
    return status;
}

int ssx_fmu_get_last_successful_time(ssx_fmu *fmu, double *time)
{
    if (time == NULL || !live(fmu, "fmi2GetRealStatus")) {
        return -1;
    }
    if (fmu->fn.get_real_status == NULL) {
        note(fmu, "this FMU does not provide fmi2GetRealStatus");
        return -1;
    }
    return outcome(fmu, fmu->fn.get_real_status(fmu->instance, fmi2LastSuccessfulTime, time));
}

int ssx_fmu_is_dead(const ssx_fmu *fmu)
{
    return fmu != NULL && fmu->fatal_call != NULL;
}

int ssx_fmu_is_instantiated(const ssx_fmu *fmu)
{
    return fmu != NULL && fmu->instance != NULL;
}

const char *ssx_fmu_last_message(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->last_message : "";
}

void ssx_fmu_get_counters(const ssx_fmu *fmu, ssx_fmu_counters *out)
{
    if (fmu != NULL && out != NULL) {
        *out = fmu->counters;
    }
}

long ssx_fmu_generation(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->generation : 0;
}

long ssx_fmu_values_epoch(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->values_epoch : 0;
}

const char *ssx_fmu_instance_name(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->instance_name : "";
}

ssx_remote *ssx_fmu_remote(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->remote : NULL;
}
