/* The FMU binding: one loaded binary (loaded here, or run by a host process), the functions
 * its back-end resolved, at most one live instance, counters of every call and the last message
 * the FMU logged. Version-neutral: the FMI standard's functions and types are the back-end's
 * (fmu_backend.h); every call on the instance passes the one check below. */
#define _POSIX_C_SOURCE 200809L

#include "fmu_binding.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "array.h"
#include "fmu_backend.h"
#include "fmu_environment.h"
#include "fmu_remote.h"
#include "shared_library.h"
#include "round_up.h"
#include "slot_pool.h"

/* A slot number for "no call yet" (last_slot). */
enum { NO_CALL = -1 };
/* The binding is aligned to cache lines of this size (the common one). */
enum { CACHE_LINE = 64 };

/* What no step reads: in an allocation of its own, so that a binding is small and the
 * bindings made in a pool lie close together. */
typedef struct {
    const char *names[SLOT_COUNT]; /* the standard's name of each slot, for messages */
    void *context;                 /* the back-end's, outlives every instance */
    void *library;
    char *guid;
    char *resource_uri;
    char *instance_name;
    int logging_on;
    /* the tolerance of the last fmi2SetupExperiment, which a Model Exchange FMU's integrator
     * uses */
    int tolerance_defined;
    double tolerance;
    /* between a completed enterInitializationMode and the exitInitializationMode after it */
    int in_initialization_mode;
    int reads_in_initialization_mode; /* see ssx_fmu_reads_in_initialization_mode */
    /* FMU states handed out by the live instance, freed with it */
    void **states;
    size_t n_states;
    size_t states_capacity;
    /* the FMU's callbacks' environment: its last message and, isolated, its host */
    ssx_fmu_environment environment;
} binding_rest;

struct ssx_fmu {
    /* What every doStep, Get and Set touches, in the struct's first two cache lines (it is
     * allocated aligned to them): where thousands of FMUs step in turn, each costs one trip to
     * memory, not one per field. The step's own functions lead the function table
     * (fmu_backend.h orders the slots so). */
    const ssx_fmu_backend *backend;
    void *instance;
    long values_epoch; /* see ssx_fmu_values_epoch */
    /* the call that returned Fatal, or NULL: after it FMI allows no call at all, not even
     * freeing the instance, so the instance and its states are abandoned (instance NULL) and
     * the library stays loaded */
    const char *fatal_call;
    int last_slot; /* the last call made or refused (an ssx_fmu_slot), NO_CALL before any */
    ssx_fmu_counters counters;
    ssx_fmu_function fn[SLOT_COUNT]; /* NULL: the binary lacks the function */
    long generation;
    long starts; /* see ssx_fmu_starts */
    slot_pool *pool; /* the pool it lies in (ssx_fmu_load_spec), NULL: allocated alone */
    binding_rest *rest;
};

/* ------------------------------------------------------------------ status names */

/* The status names without a standard's prefix: what Python shows. */
#define NEUTRAL_NAME(name) #name,
static const char *const status_names[] = {SSX_STATUS_NAMES(NEUTRAL_NAME)};

const char *ssx_status_name(int status)
{
    if (status >= 0 && status < (int)(sizeof status_names / sizeof status_names[0])) {
        return status_names[status];
    }
    return status == -1 ? "failed" : NULL;
}

/* ------------------------------------------------------------------ messages */

static void note(ssx_fmu *fmu, const char *text)
{
    ssx_fmu_environment *environment = &fmu->rest->environment;
    snprintf(environment->last_message, sizeof environment->last_message, "%s", text);
}

/* ------------------------------------------------------------------ loading */

static char *duplicate(const char *text)
{
    return strdup(text != NULL ? text : "");
}

/* Unprefixed names first; FMUs compiled with a function prefix export <id>_<name>. */
static void *resolve(void *library, const char *model_identifier, const char *name)
{
    void *symbol = shared_library_symbol(library, name);
    if (symbol == NULL && model_identifier[0] != '\0') {
        char prefixed[256];
        snprintf(prefixed, sizeof prefixed, "%s_%s", model_identifier, name);
        symbol = shared_library_symbol(library, prefixed);
    }
    return symbol;
}

/* The name of a slot the back-end's table lacks (a Model Exchange FMU's fmi2DoStep). */
static const char OUTSIDE_THE_INTERFACE[] = "a function outside the FMU's interface";

/* Fills the slots from the back-end's table: from the library, or the forwarders of an
 * isolated FMU's host. A required function that is missing is the error. */
static int resolve_functions(ssx_fmu *fmu, const char *binary_path,
                             const char *model_identifier, char *error, size_t error_size)
{
    const ssx_fmu_backend *backend = fmu->backend;
    for (int slot = 0; slot < SLOT_COUNT; ++slot) {
        fmu->rest->names[slot] = OUTSIDE_THE_INTERFACE;
    }
    for (size_t i = 0; i < backend->n_functions; ++i) {
        const ssx_fmu_function_row *row = &backend->functions[i];
        ssx_remote *remote = fmu->rest->environment.remote;
        void *symbol = remote != NULL ? ssx_remote_function(remote, row->name)
                                      : resolve(fmu->rest->library, model_identifier, row->name);
        /* a symbol is a void *; C11 has no direct cast to a function pointer */
        memcpy(&fmu->fn[row->slot], &symbol, sizeof symbol);
        fmu->rest->names[row->slot] = row->name;
        if (symbol == NULL && row->required) {
            snprintf(error, error_size, "%s does not export %s: not an %s binary", binary_path,
                     row->name, backend->standard);
            return -1;
        }
    }
    return 0;
}

static void unload(void *library, ssx_remote *remote)
{
    if (remote != NULL) {
        ssx_remote_stop(remote);
    } else if (library != NULL) {
        shared_library_close(library);
    }
}

/* The back-end of each standard's interfaces (NULL: not one syssimx runs). */
static const ssx_fmu_backend *backend_of(const ssx_fmu_load_spec *spec)
{
    static const ssx_fmu_backend *const backends[][3] = {
        [SSX_FMI1] = {&ssx_fmi1_backend, &ssx_fmi1_model_exchange_backend, NULL},
        [SSX_FMI2] = {&ssx_fmi2_backend, &ssx_fmi2_model_exchange_backend, NULL},
        [SSX_FMI3] = {&ssx_fmi3_backend, &ssx_fmi3_model_exchange_backend,
                      &ssx_fmi3_scheduled_backend},
    };
    size_t n_versions = sizeof backends / sizeof backends[0];
    if ((size_t)spec->version >= n_versions ||
        (spec->interface != SSX_CO_SIMULATION && spec->interface != SSX_MODEL_EXCHANGE &&
         spec->interface != SSX_SCHEDULED_EXECUTION)) {

        return NULL;
    }
    return backends[spec->version][spec->interface];
}

/* A spec the binding cannot load from, named; NULL when it can. */
static const char *unusable(const ssx_fmu_load_spec *spec, const ssx_fmu_backend *backend)
{
    if (spec->binary_path == NULL || spec->model_identifier == NULL) {
        return "the binary path and the model identifier are required";
    }
    if (backend == NULL) {
        return "the FMI version or interface is not one syssimx runs";
    }
    if (spec->host_path != NULL && backend != &ssx_fmi2_backend &&
        backend != &ssx_fmi1_backend) {
        return "only FMI 2.0 and FMI 1.0 Co-Simulation FMUs run in a host process";
    }
    return NULL;
}

static void release_binding(ssx_fmu *fmu)
{
    free(fmu->rest);
    if (fmu->pool != NULL) {
        slot_pool_give_back(fmu->pool, fmu);
    } else {
        free(fmu);
    }
}

/* ------------------------------------------------------------------ where bindings lie */

struct ssx_binding_pool {
    slot_pool *slots;
};

ssx_binding_pool *ssx_binding_pool_new(void)
{
    ssx_binding_pool *pool = malloc(sizeof *pool);
    if (pool == NULL) {
        return NULL;
    }
    pool->slots = slot_pool_new(sizeof(ssx_fmu), CACHE_LINE);
    if (pool->slots == NULL) {
        free(pool);
        return NULL;
    }
    return pool;
}

void ssx_binding_pool_release(ssx_binding_pool *pool)
{
    if (pool != NULL) {
        slot_pool_release(pool->slots); /* its bindings keep the slots until they are freed */
        free(pool);
    }
}

/* A zeroed binding in `pool` (NULL: on its own), aligned to cache lines, with its rest. */
static ssx_fmu *allocate_binding(ssx_binding_pool *pool)
{
    ssx_fmu *fmu;
    if (pool != NULL) {
        fmu = slot_pool_take(pool->slots);
    } else {
        fmu = aligned_alloc(CACHE_LINE, round_up(sizeof *fmu, CACHE_LINE));
        if (fmu != NULL) {
            memset(fmu, 0, sizeof *fmu);
        }
    }
    if (fmu == NULL) {
        return NULL;
    }
    fmu->pool = pool != NULL ? pool->slots : NULL;
    fmu->rest = calloc(1, sizeof *fmu->rest);
    if (fmu->rest == NULL) {
        release_binding(fmu);
        return NULL;
    }
    return fmu;
}

ssx_fmu *ssx_fmu_load(const ssx_fmu_load_spec *spec, char *error, size_t error_size)
{
    if (spec == NULL) {
        snprintf(error, error_size, "ssx_fmu_load: no load spec");
        return NULL;
    }
    const ssx_fmu_backend *backend = backend_of(spec);
    const char *problem = unusable(spec, backend);
    if (problem != NULL) {
        snprintf(error, error_size, "ssx_fmu_load: %s", problem);
        return NULL;
    }
    ssx_fmu *fmu = allocate_binding(spec->binding_pool);
    if (fmu == NULL) {
        snprintf(error, error_size, "out of memory loading %s", spec->binary_path);
        return NULL;
    }
    fmu->backend = backend;
    fmu->last_slot = NO_CALL;
    if (spec->host_path != NULL) {
        fmu->rest->environment.remote = ssx_remote_start(spec->host_path, spec->binary_path,
                                       spec->model_identifier,
                                       backend == &ssx_fmi1_backend, spec->step_timeout,
                                       error, error_size);
        if (fmu->rest->environment.remote == NULL) {
            release_binding(fmu);
            return NULL;
        }
    } else {
        const char *reason = NULL;
        fmu->rest->library = shared_library_open(spec->binary_path, &reason);
        if (fmu->rest->library == NULL) {
            snprintf(error, error_size, "cannot load the FMU binary %s: %s", spec->binary_path,
                     reason);
            release_binding(fmu);
            return NULL;
        }
    }
    if (resolve_functions(fmu, spec->binary_path, spec->model_identifier, error,
                          error_size) != 0) {
        ssx_fmu_free(fmu);
        return NULL;
    }
    fmu->rest->context = calloc(1, backend->context_size);
    fmu->rest->guid = duplicate(spec->guid);
    fmu->rest->resource_uri = duplicate(spec->resource_location);
    fmu->rest->instance_name = duplicate(spec->instance_name != NULL ? spec->instance_name
                                                               : spec->model_identifier);
    if (fmu->rest->context == NULL || fmu->rest->guid == NULL || fmu->rest->resource_uri == NULL ||
        fmu->rest->instance_name == NULL) {
        snprintf(error, error_size, "out of memory loading %s", spec->binary_path);
        ssx_fmu_free(fmu);
        return NULL;
    }
    fmu->rest->logging_on = spec->logging_on;
    fmu->rest->reads_in_initialization_mode = spec->version != SSX_FMI1;
    if (backend->prepare != NULL &&
        backend->prepare(fmu->rest->context, spec, error, error_size) != 0) {
        ssx_fmu_free(fmu);
        return NULL;
    }
    return fmu;
}

/* ------------------------------------------------------------------ the checked call */

/* What a call changes besides the FMU: the counter it bumps (an offset into ssx_fmu_counters)
 * and whether it may change the instance's inputs (ssx_fmu_values_epoch). */
#define COUNTED(field) (offsetof(ssx_fmu_counters, field) + 1)
static const struct {
    size_t counter; /* COUNTED(field), 0 for none */
    int sets_values;
} effects[SLOT_COUNT] = {
    [SLOT_INSTANTIATE] = {COUNTED(instantiate), 1},
    [SLOT_GET_REAL] = {COUNTED(get_values), 0},
    [SLOT_GET_INTEGER] = {COUNTED(get_values), 0},
    [SLOT_GET_BOOLEAN] = {COUNTED(get_values), 0},
    [SLOT_SET_REAL] = {COUNTED(set_values), 1},
    [SLOT_SET_INTEGER] = {COUNTED(set_values), 1},
    [SLOT_SET_BOOLEAN] = {COUNTED(set_values), 1},
    [SLOT_DO_STEP] = {COUNTED(do_step), 0},
    [SLOT_GET_STATE] = {COUNTED(get_state), 0},
    [SLOT_SET_STATE] = {COUNTED(set_state), 1},
    [SLOT_DIRECTIONAL_DERIVATIVE] = {COUNTED(directional_derivative), 0},
    [SLOT_SET_INPUT_DERIVATIVES] = {COUNTED(set_values), 0},
    [SLOT_GET_OUTPUT_DERIVATIVES] = {COUNTED(get_values), 0},
    [SLOT_RESET] = {COUNTED(reset), 1},
    [SLOT_GET_STRING] = {COUNTED(get_values), 0},
    [SLOT_GET_BINARY] = {COUNTED(get_values), 0},
    [SLOT_SET_STRING] = {COUNTED(set_values), 1},
    [SLOT_SET_BINARY] = {COUNTED(set_values), 1},
};

static void refuse_after_fatal(ssx_fmu *fmu, const char *call)
{
    snprintf(fmu->rest->environment.last_message, sizeof fmu->rest->environment.last_message,
             "%s refused: %s returned %s earlier, and %s allows no further call on the FMU", call,
             fmu->fatal_call, fmu->backend->status_names[SSX_STATUS_FATAL],
             fmu->backend->version);
}

/* Why a call was refused, as the FMU's last message. */
static int refuse(ssx_fmu *fmu, ssx_fmu_slot call)
{
    const char *name = fmu->rest->names[call];
    char *message = fmu->rest->environment.last_message;
    size_t size = sizeof fmu->rest->environment.last_message;
    if (fmu->fatal_call != NULL) {
        refuse_after_fatal(fmu, name);
    } else if (name == OUTSIDE_THE_INTERFACE) {
        snprintf(message, size, "the FMU runs as %s, which has no such function",
                 fmu->backend->standard);
    } else if (fmu->instance == NULL) {
        snprintf(message, size, "%s called without a live instance (call instantiate first)", name);
    } else {
        snprintf(message, size, "this FMU does not provide %s", name);
    }
    return 0;
}

/* Every call on the instance starts here: refused without a live instance or when the binary
 * lacks the function; else the call is marked as this thread's, for the FMU's callbacks
 * (fmu_environment.h), until finish or refused_after_begin. Inline: it runs before every
 * doStep. */
static inline int begin(ssx_fmu *fmu, ssx_fmu_slot call)
{
    if (fmu == NULL) {
        return 0;
    }
    fmu->last_slot = (int)call;
    if (fmu->instance == NULL || fmu->fn[call] == NULL) {
        return refuse(fmu, call);
    }
    ssx_fmu_environment_enter(&fmu->rest->environment);
    return 1;
}

/* A call begun and then refused by the binding, before the FMU was called. */
static int refused_after_begin(void)
{
    ssx_fmu_environment_leave();
    return -1;
}

static void abandon(ssx_fmu *fmu, ssx_fmu_slot call)
{
    fmu->fatal_call = fmu->rest->names[call];
    fmu->instance = NULL;
    fmu->rest->n_states = 0;
}

/* ... and ends here with the status the instance returned: counted, and a fatal one ends all
 * calls. `call` is a constant at every use, so the counting folds away. */
static inline int finish(ssx_fmu *fmu, ssx_fmu_slot call, int status)
{
    ssx_fmu_environment_leave();
    if (effects[call].counter != 0) {
        long *counter = (long *)((char *)&fmu->counters + effects[call].counter - 1);
        ++*counter;
    }
    fmu->values_epoch += effects[call].sets_values;
    if (status == SSX_STATUS_FATAL) {
        abandon(fmu, call);
    }
    return status;
}

/* The call of `slot` through the back-end's adapter, checked. */
#define CHECKED(fmu, slot, adapter, ...)                                                      \
    (begin((fmu), (slot)) ? finish((fmu), (slot),                                             \
                                   (fmu)->backend->adapter((fmu)->fn, (fmu)->instance,        \
                                                           __VA_ARGS__))                      \
                          : -1)
#define CHECKED0(fmu, slot, adapter)                                                          \
    (begin((fmu), (slot)) ? finish((fmu), (slot),                                             \
                                   (fmu)->backend->adapter((fmu)->fn, (fmu)->instance))       \
                          : -1)

/* ------------------------------------------------------------------ life cycle */

static int forget_state(ssx_fmu *fmu, void *state)
{
    for (size_t i = 0; i < fmu->rest->n_states; ++i) {
        if (fmu->rest->states[i] == state) {
            fmu->rest->states[i] = fmu->rest->states[--fmu->rest->n_states];
            return 0;
        }
    }
    return -1;
}

static int knows_state(const ssx_fmu *fmu, const void *state)
{
    for (size_t i = 0; i < fmu->rest->n_states; ++i) {
        if (fmu->rest->states[i] == state) {
            return 1;
        }
    }
    return 0;
}

static int remember_state(ssx_fmu *fmu, void *state)
{
    binding_rest *rest = fmu->rest;
    if (array_reserve((void **)&rest->states, &rest->states_capacity, rest->n_states + 1,
                      sizeof *rest->states, 4) != 0) {
        return -1;
    }
    rest->states[rest->n_states++] = state;
    return 0;
}

int ssx_fmu_free_instance(ssx_fmu *fmu)
{
    if (fmu == NULL) {
        return -1;
    }
    int worst = 0;
    if (fmu->instance != NULL) {
        ssx_fmu_environment_enter(&fmu->rest->environment);
        /* States belong to their instance: release them while it still exists. */
        while (fmu->rest->n_states > 0) {
            void *state = fmu->rest->states[--fmu->rest->n_states];
            if (fmu->fn[SLOT_FREE_STATE] != NULL) {
                int status = fmu->backend->free_state(fmu->fn, fmu->instance, &state);
                worst = status > worst ? status : worst;
            }
        }
        fmu->backend->free_instance(fmu->fn, fmu->instance);
        fmu->instance = NULL;
        ssx_fmu_environment_leave();
    }
    return worst; /* the worst status of freeing the states; the instance is gone either way */
}

void ssx_fmu_free(ssx_fmu *fmu)
{
    if (fmu == NULL) {
        return;
    }
    if (fmu->instance != NULL) {
        /* Teardown goes on whatever the FMU answers: there is no one left to report to. */
        ssx_fmu_environment_enter(&fmu->rest->environment);
        (void)fmu->backend->terminate(fmu->fn, fmu->instance);
        ssx_fmu_environment_leave();
    }
    (void)ssx_fmu_free_instance(fmu);
    free(fmu->rest->states);
    if (fmu->rest->context != NULL && fmu->backend->release_context != NULL) {
        fmu->backend->release_context(fmu->rest->context);
    }
    free(fmu->rest->context);
    free(fmu->rest->guid);
    free(fmu->rest->resource_uri);
    free(fmu->rest->instance_name);
    /* unloading would run the code of a library that declared itself broken; a host process
     * can always be ended */
    if (fmu->fatal_call == NULL || fmu->rest->environment.remote != NULL) {
        unload(fmu->rest->library, fmu->rest->environment.remote);
    }
    release_binding(fmu);
}

int ssx_fmu_instantiate(ssx_fmu *fmu)
{
    if (fmu == NULL) {
        return -1;
    }
    fmu->last_slot = SLOT_INSTANTIATE;
    if (fmu->fatal_call != NULL && fmu->rest->environment.remote == NULL) {
        refuse_after_fatal(fmu, fmu->rest->names[SLOT_INSTANTIATE]);
        return -1;
    }
    if (fmu->fatal_call != NULL) {
        /* an isolated FMU starts over in a new host: the broken one is ended, never called */
        ssx_remote_restart(fmu->rest->environment.remote);
        fmu->fatal_call = NULL;
    }
    /* a state the old instance fails to free is its leak, not a reason to refuse a new one */
    (void)ssx_fmu_free_instance(fmu);
    fmu->rest->environment.last_message[0] = '\0';
    fmu->rest->in_initialization_mode = 0;
    binding_rest *rest = fmu->rest;
    ssx_fmu_environment_enter(&rest->environment);
    fmu->instance = fmu->backend->instantiate(fmu->fn, rest->context, &rest->environment,
                                              rest->instance_name, rest->guid,
                                              rest->resource_uri, rest->logging_on);
    (void)finish(fmu, SLOT_INSTANTIATE, 0);
    fmu->generation++;
    fmu->starts++;
    if (fmu->instance == NULL) {
        if (rest->environment.last_message[0] == '\0') {
            snprintf(rest->environment.last_message, sizeof rest->environment.last_message,
                     "%s returned NULL", rest->names[SLOT_INSTANTIATE]);
        }
        return -1;
    }
    return 0;
}

int ssx_fmu_setup_experiment(ssx_fmu *fmu, int tolerance_defined, double tolerance,
                             double start_time, int stop_time_defined, double stop_time)
{
    if (fmu != NULL) {
        fmu->rest->tolerance_defined = tolerance_defined;
        fmu->rest->tolerance = tolerance;
    }
    return CHECKED(fmu, SLOT_SETUP_EXPERIMENT, setup_experiment, tolerance_defined, tolerance,
                   start_time, stop_time_defined, stop_time);
}

int ssx_fmu_enter_initialization_mode(ssx_fmu *fmu)
{
    int status = CHECKED0(fmu, SLOT_ENTER_INITIALIZATION_MODE, enter_initialization_mode);
    if (status == 0 || status == 1) { /* OK or Warning */
        fmu->rest->in_initialization_mode = 1;
    }
    return status;
}

int ssx_fmu_exit_initialization_mode(ssx_fmu *fmu)
{
    if (fmu != NULL) {
        fmu->rest->in_initialization_mode = 0; /* whatever it answers, it is not asked again */
    }
    return CHECKED0(fmu, SLOT_EXIT_INITIALIZATION_MODE, exit_initialization_mode);
}

int ssx_fmu_in_initialization_mode(const ssx_fmu *fmu)
{
    return fmu->rest->in_initialization_mode;
}

int ssx_fmu_reads_in_initialization_mode(const ssx_fmu *fmu)
{
    return fmu->rest->reads_in_initialization_mode;
}

int ssx_fmu_reset(ssx_fmu *fmu)
{
    int status = CHECKED0(fmu, SLOT_RESET, reset);
    if (status == 0 || status == 1) { /* OK or Warning */
        fmu->starts++;
        fmu->rest->in_initialization_mode = 0;
    }
    return status;
}

int ssx_fmu_terminate(ssx_fmu *fmu)
{
    return CHECKED0(fmu, SLOT_TERMINATE, terminate);
}

/* ------------------------------------------------------------------ stepping and values */

int ssx_fmu_do_step(ssx_fmu *fmu, double t, double h, int no_set_fmu_state_prior)
{
    return CHECKED(fmu, SLOT_DO_STEP, do_step, t, h, no_set_fmu_state_prior);
}

int ssx_fmu_get_real(ssx_fmu *fmu, const unsigned int *vr, size_t n, double *values)
{
    return CHECKED(fmu, SLOT_GET_REAL, get_real, vr, n, values);
}

int ssx_fmu_set_real(ssx_fmu *fmu, const unsigned int *vr, size_t n, const double *values)
{
    return CHECKED(fmu, SLOT_SET_REAL, set_real, vr, n, values);
}

int ssx_fmu_get_integer(ssx_fmu *fmu, const unsigned int *vr, size_t n, int *values)
{
    return CHECKED(fmu, SLOT_GET_INTEGER, get_integer, vr, n, values);
}

int ssx_fmu_set_integer(ssx_fmu *fmu, const unsigned int *vr, size_t n, const int *values)
{
    return CHECKED(fmu, SLOT_SET_INTEGER, set_integer, vr, n, values);
}

int ssx_fmu_get_boolean(ssx_fmu *fmu, const unsigned int *vr, size_t n, int *values)
{
    return CHECKED(fmu, SLOT_GET_BOOLEAN, get_boolean, vr, n, values);
}

int ssx_fmu_set_boolean(ssx_fmu *fmu, const unsigned int *vr, size_t n, const int *values)
{
    return CHECKED(fmu, SLOT_SET_BOOLEAN, set_boolean, vr, n, values);
}

int ssx_fmu_get_directional_derivative(ssx_fmu *fmu, const unsigned int *unknowns,
                                       size_t n_unknowns, const unsigned int *knowns,
                                       size_t n_knowns, const double *dv_known,
                                       double *dv_unknown)
{
    return CHECKED(fmu, SLOT_DIRECTIONAL_DERIVATIVE, directional_derivative, unknowns,
                   n_unknowns, knowns, n_knowns, dv_known, dv_unknown);
}

int ssx_fmu_set_real_input_derivatives(ssx_fmu *fmu, const unsigned int *vr, size_t n,
                                       const int *order, const double *values)
{
    return CHECKED(fmu, SLOT_SET_INPUT_DERIVATIVES, set_input_derivatives, vr, n, order, values);
}

int ssx_fmu_get_real_output_derivatives(ssx_fmu *fmu, const unsigned int *vr, size_t n,
                                        const int *order, double *values)
{
    return CHECKED(fmu, SLOT_GET_OUTPUT_DERIVATIVES, get_output_derivatives, vr, n, order,
                   values);
}

int ssx_fmu_get_terminated(ssx_fmu *fmu, int *terminated)
{
    if (terminated == NULL) {
        return -1;
    }
    return CHECKED(fmu, SLOT_GET_TERMINATED, get_terminated, terminated);
}

int ssx_fmu_get_last_successful_time(ssx_fmu *fmu, double *time)
{
    if (time == NULL) {
        return -1;
    }
    return CHECKED(fmu, SLOT_GET_LAST_SUCCESSFUL_TIME, get_last_successful_time, time);
}

int ssx_fmu_get_string(ssx_fmu *fmu, const unsigned int *vr, size_t n, const char **values)
{
    return CHECKED(fmu, SLOT_GET_STRING, get_string, vr, n, values);
}

int ssx_fmu_set_string(ssx_fmu *fmu, const unsigned int *vr, size_t n, const char *const *values)
{
    return CHECKED(fmu, SLOT_SET_STRING, set_string, vr, n, values);
}

int ssx_fmu_get_binary(ssx_fmu *fmu, const unsigned int *vr, size_t n, size_t *sizes,
                       const unsigned char **values)
{
    return CHECKED(fmu, SLOT_GET_BINARY, get_binary, vr, n, sizes, values);
}

int ssx_fmu_set_binary(ssx_fmu *fmu, const unsigned int *vr, size_t n, const size_t *sizes,
                       const unsigned char *const *values)
{
    return CHECKED(fmu, SLOT_SET_BINARY, set_binary, vr, n, sizes, values);
}

/* ------------------------------------------------------------------ events (FMI 3.0) */

void ssx_fmu_step_outcome(const ssx_fmu *fmu, fmu_step_outcome *outcome)
{
    *outcome = (fmu_step_outcome){0};
    if (fmu != NULL && fmu->instance != NULL && fmu->backend->step_outcome != NULL) {
        fmu->backend->step_outcome(fmu->instance, outcome);
    }
}

/* ------------------------------------------------------------------ Model Exchange */

int ssx_fmu_set_time(ssx_fmu *fmu, double time)
{
    return CHECKED(fmu, SLOT_SET_TIME, set_time, time);
}

int ssx_fmu_set_continuous_states(ssx_fmu *fmu, const double *x, size_t nx)
{
    return CHECKED(fmu, SLOT_SET_CONTINUOUS_STATES, set_continuous_states, x, nx);
}

int ssx_fmu_get_continuous_states(ssx_fmu *fmu, double *x, size_t nx)
{
    return CHECKED(fmu, SLOT_GET_CONTINUOUS_STATES, get_continuous_states, x, nx);
}

int ssx_fmu_get_derivatives(ssx_fmu *fmu, double *dx, size_t nx)
{
    return CHECKED(fmu, SLOT_GET_DERIVATIVES, get_derivatives, dx, nx);
}

int ssx_fmu_get_event_indicators(ssx_fmu *fmu, double *z, size_t nz)
{
    return CHECKED(fmu, SLOT_GET_EVENT_INDICATORS, get_event_indicators, z, nz);
}

int ssx_fmu_get_nominals_of_continuous_states(ssx_fmu *fmu, double *nominals, size_t nx)
{
    return CHECKED(fmu, SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES,
                   get_nominals_of_continuous_states, nominals, nx);
}

int ssx_fmu_enter_event_mode(ssx_fmu *fmu)
{
    return CHECKED0(fmu, SLOT_ENTER_EVENT_MODE, enter_event_mode);
}

int ssx_fmu_new_discrete_states(ssx_fmu *fmu, ssx_fmu_event_info *info)
{
    return CHECKED(fmu, SLOT_NEW_DISCRETE_STATES, new_discrete_states, info);
}

int ssx_fmu_enter_step_mode(ssx_fmu *fmu)
{
    return CHECKED0(fmu, SLOT_ENTER_STEP_MODE, enter_step_mode);
}

int ssx_fmu_tick_clocks(ssx_fmu *fmu, double t)
{
    return CHECKED(fmu, SLOT_SET_CLOCK, tick_clocks, t);
}

double ssx_fmu_next_clock_tick(const ssx_fmu *fmu, double t)
{
    if (fmu == NULL || fmu->instance == NULL || fmu->backend->next_clock_tick == NULL) {
        return INFINITY;
    }
    return fmu->backend->next_clock_tick(fmu->instance, t);
}

int ssx_fmu_read_output_clocks(ssx_fmu *fmu, int *active)
{
    return CHECKED(fmu, SLOT_GET_CLOCK, read_output_clocks, active);
}

int ssx_fmu_tick_triggered_clock(ssx_fmu *fmu, size_t clock)
{
    return CHECKED(fmu, SLOT_SET_CLOCK, tick_triggered_clock, clock);
}

int ssx_fmu_plan_clocks(ssx_fmu *fmu, double t)
{
    if (fmu != NULL && (fmu->backend->countdown_clocks == NULL ||
                        fmu->backend->countdown_clocks(fmu->rest->context) == 0)) {
        return 0; /* nothing to ask: fmi3GetIntervalDecimal is not needed */
    }
    return CHECKED(fmu, SLOT_GET_INTERVAL, plan_clocks, t);
}

int ssx_fmu_activate_model_partition(ssx_fmu *fmu, unsigned int clock, double t)
{
    return CHECKED(fmu, SLOT_ACTIVATE_MODEL_PARTITION, activate_model_partition, clock, t);
}

void ssx_fmu_take_clock_updates(ssx_fmu *fmu, int *ticked, double *next)
{
    if (fmu->backend->take_clock_updates != NULL) {
        fmu->backend->take_clock_updates(fmu->rest->context, ticked, next);
    }
}

int ssx_fmu_get_interval(ssx_fmu *fmu, unsigned int clock, double *interval, int *qualifier)
{
    return CHECKED(fmu, SLOT_GET_INTERVAL, get_interval, clock, interval, qualifier);
}

size_t ssx_fmu_countdown_clock_count(const ssx_fmu *fmu)
{
    return fmu->backend->countdown_clocks != NULL ? fmu->backend->countdown_clocks(fmu->rest->context)
                                                  : 0;
}

void ssx_fmu_clock_counts(const ssx_fmu *fmu, size_t *n_output, size_t *n_triggered)
{
    *n_output = 0;
    *n_triggered = 0;
    if (fmu->backend->clock_counts != NULL) {
        fmu->backend->clock_counts(fmu->rest->context, n_output, n_triggered);
    }
}

int ssx_fmu_enter_continuous_time_mode(ssx_fmu *fmu)
{
    return CHECKED0(fmu, SLOT_ENTER_CONTINUOUS_TIME_MODE, enter_continuous_time_mode);
}

int ssx_fmu_completed_integrator_step(ssx_fmu *fmu, int no_set_state_prior,
                                      int *enter_event_mode, int *terminate_simulation)
{
    return CHECKED(fmu, SLOT_COMPLETED_INTEGRATOR_STEP, completed_integrator_step,
                   no_set_state_prior, enter_event_mode, terminate_simulation);
}

int ssx_fmu_get_number_of_continuous_states(ssx_fmu *fmu, size_t *n)
{
    return CHECKED(fmu, SLOT_GET_NUMBER_OF_CONTINUOUS_STATES, get_number_of_continuous_states, n);
}

int ssx_fmu_get_number_of_event_indicators(ssx_fmu *fmu, size_t *n)
{
    return CHECKED(fmu, SLOT_GET_NUMBER_OF_EVENT_INDICATORS, get_number_of_event_indicators, n);
}

int ssx_fmu_experiment_tolerance(const ssx_fmu *fmu, double *tolerance)
{
    if (fmu == NULL || !fmu->rest->tolerance_defined) {
        return 0;
    }
    *tolerance = fmu->rest->tolerance;
    return 1;
}

int ssx_fmu_is_model_exchange(const ssx_fmu *fmu)
{
    return fmu != NULL && fmu->backend->interface == SSX_MODEL_EXCHANGE;
}

/* ------------------------------------------------------------------ states */

int ssx_fmu_get_state(ssx_fmu *fmu, void **state)
{
    if (state == NULL || !begin(fmu, SLOT_GET_STATE)) {
        return -1;
    }
    if (*state != NULL && !knows_state(fmu, *state)) {
        snprintf(fmu->rest->environment.last_message, sizeof fmu->rest->environment.last_message,
                 "%s: the state to reuse does not belong to the live instance",
                 ssx_fmu_last_call(fmu));
        return refused_after_begin();
    }
    void *reused = *state;
    int status =
        finish(fmu, SLOT_GET_STATE, fmu->backend->get_state(fmu->fn, fmu->instance, state));
    if (reused != NULL && *state != reused) {
        /* the FMU may move a state it updates (the Reference FMUs realloc it) */
        (void)forget_state(fmu, reused);
    }
    if (*state != reused && *state != NULL && remember_state(fmu, *state) != 0) {
        if (fmu->fn[SLOT_FREE_STATE] != NULL) {
            ssx_fmu_environment_enter(&fmu->rest->environment);
            fmu->backend->free_state(fmu->fn, fmu->instance, state);
            ssx_fmu_environment_leave();
        }
        note(fmu, "out of memory tracking FMU states");
        return -1;
    }
    return status;
}

int ssx_fmu_set_state(ssx_fmu *fmu, void *state)
{
    if (!begin(fmu, SLOT_SET_STATE)) {
        return -1;
    }
    if (!knows_state(fmu, state)) {
        snprintf(fmu->rest->environment.last_message, sizeof fmu->rest->environment.last_message,
                 "%s: the state does not belong to the live instance", ssx_fmu_last_call(fmu));
        return refused_after_begin();
    }
    return finish(fmu, SLOT_SET_STATE, fmu->backend->set_state(fmu->fn, fmu->instance, state));
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
     * abandoned after a fatal status may not be released at all). */
    if (forget_state(fmu, *state) != 0) {
        *state = NULL;
        return 0;
    }
    return CHECKED(fmu, SLOT_FREE_STATE, free_state, state);
}

int ssx_fmu_serialized_state_size(ssx_fmu *fmu, void *state, size_t *size)
{
    return CHECKED(fmu, SLOT_SERIALIZED_STATE_SIZE, serialized_state_size, state, size);
}

int ssx_fmu_serialize_state(ssx_fmu *fmu, void *state, char *bytes, size_t size)
{
    return CHECKED(fmu, SLOT_SERIALIZE_STATE, serialize_state, state, bytes, size);
}

int ssx_fmu_deserialize_state(ssx_fmu *fmu, const char *bytes, size_t size, void **state)
{
    if (state == NULL || !begin(fmu, SLOT_DESERIALIZE_STATE)) {
        return -1;
    }
    if (*state != NULL && !knows_state(fmu, *state)) {
        snprintf(fmu->rest->environment.last_message, sizeof fmu->rest->environment.last_message,
                 "%s: the state to reuse does not belong to the live instance",
                 ssx_fmu_last_call(fmu));
        return refused_after_begin();
    }
    void *reused = *state;
    int status = finish(fmu, SLOT_DESERIALIZE_STATE,
                        fmu->backend->deserialize_state(fmu->fn, fmu->instance, bytes, size,
                                                        state));
    if (reused != NULL && *state != reused) {
        /* as in ssx_fmu_get_state: the FMU may move a state it overwrites */
        (void)forget_state(fmu, reused);
    }
    if (*state != reused && *state != NULL && remember_state(fmu, *state) != 0) {
        note(fmu, "out of memory tracking FMU states");
        return -1;
    }
    return status;
}

/* ------------------------------------------------------------------ queries */

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
    return fmu != NULL ? fmu->rest->environment.last_message : "";
}

const char *ssx_fmu_last_call(const ssx_fmu *fmu)
{
    return fmu == NULL || fmu->last_slot == NO_CALL ? "" : fmu->rest->names[fmu->last_slot];
}

void ssx_fmu_get_counters(const ssx_fmu *fmu, ssx_fmu_counters *out)
{
    if (fmu != NULL && out != NULL) {
        *out = fmu->counters;
    }
}

const char *ssx_fmu_status_text(const ssx_fmu *fmu, int status)
{
    if (fmu == NULL || fmu->backend == &ssx_fmi2_backend) {
        return ssx_fmi2_status_name(status);
    }
    if (status >= 0 && status <= SSX_STATUS_FATAL + 1) {
        return fmu->backend->status_names[status];
    }
    return "no status (the engine failed)";
}

const char *ssx_fmu_variable_name(const ssx_fmu *fmu, unsigned int vr)
{
    const char *name = NULL;
    if (fmu != NULL && fmu->rest->context != NULL && fmu->backend->variable_name != NULL) {
        name = fmu->backend->variable_name(fmu->rest->context, vr);
    }
    return name != NULL ? name : "";
}

const char *ssx_fmu_function_name(const ssx_fmu *fmu, int slot)
{
    if (fmu == NULL || slot < 0 || slot >= SLOT_COUNT ||
        fmu->rest->names[slot] == OUTSIDE_THE_INTERFACE) {
        return "";
    }
    return fmu->rest->names[slot];
}

long ssx_fmu_generation(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->generation : 0;
}

long ssx_fmu_starts(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->starts : 0;
}

long ssx_fmu_values_epoch(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->values_epoch : 0;
}

ssx_remote *ssx_fmu_remote(const ssx_fmu *fmu)
{
    return fmu != NULL ? fmu->rest->environment.remote : NULL;
}
