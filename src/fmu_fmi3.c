/* The FMI 3.0 back-ends of the FMU binding, Co-Simulation and Model Exchange: the fmi3
 * functions, which of them a binary must export for each interface, and adapters that call
 * each with its fmi3 type.
 *
 * The engine speaks in three port types; FMI 3.0 has eleven numeric ones. The back-end keeps
 * the type of every value reference (given at load) and turns one engine call into one fmi3
 * call per FMI 3.0 type met, converting each value and refusing one that does not fit.
 *
 * FMI 3.0 passes the experiment to fmi3EnterInitializationMode and returns doStep's news in
 * out-arguments: the instance the binding holds is this back-end's context, which keeps both
 * beside the FMU's own instance. */
#include "fmu_backend.h"

#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"

/* The rows both interfaces share: required, then optional. */
#define FMI3_COMMON_ROWS                                                                      \
    {"fmi3FreeInstance", SLOT_FREE_INSTANCE, 1},                                              \
    /* the experiment is kept until fmi3EnterInitializationMode, which takes it */            \
    {"fmi3EnterInitializationMode", SLOT_SETUP_EXPERIMENT, 1},                                \
    {"fmi3EnterInitializationMode", SLOT_ENTER_INITIALIZATION_MODE, 1},                       \
    {"fmi3ExitInitializationMode", SLOT_EXIT_INITIALIZATION_MODE, 1},                         \
    {"fmi3Terminate", SLOT_TERMINATE, 1},                                                     \
    {"fmi3Reset", SLOT_RESET, 1},                                                             \
    {"fmi3GetFloat64", SLOT_GET_REAL, 1},                                                     \
    {"fmi3GetInt32", SLOT_GET_INTEGER, 1},                                                    \
    {"fmi3GetBoolean", SLOT_GET_BOOLEAN, 1},                                                  \
    {"fmi3SetFloat64", SLOT_SET_REAL, 1},                                                     \
    {"fmi3SetInt32", SLOT_SET_INTEGER, 1},                                                    \
    {"fmi3SetBoolean", SLOT_SET_BOOLEAN, 1},                                                  \
    {"fmi3GetFloat32", SLOT_GET_FLOAT32, 1},                                                  \
    {"fmi3GetInt8", SLOT_GET_INT8, 1},                                                        \
    {"fmi3GetUInt8", SLOT_GET_UINT8, 1},                                                      \
    {"fmi3GetInt16", SLOT_GET_INT16, 1},                                                      \
    {"fmi3GetUInt16", SLOT_GET_UINT16, 1},                                                    \
    {"fmi3GetUInt32", SLOT_GET_UINT32, 1},                                                    \
    {"fmi3GetInt64", SLOT_GET_INT64, 1},                                                      \
    {"fmi3GetUInt64", SLOT_GET_UINT64, 1},                                                    \
    {"fmi3SetFloat32", SLOT_SET_FLOAT32, 1},                                                  \
    {"fmi3SetInt8", SLOT_SET_INT8, 1},                                                        \
    {"fmi3SetUInt8", SLOT_SET_UINT8, 1},                                                      \
    {"fmi3SetInt16", SLOT_SET_INT16, 1},                                                      \
    {"fmi3SetUInt16", SLOT_SET_UINT16, 1},                                                    \
    {"fmi3SetUInt32", SLOT_SET_UINT32, 1},                                                    \
    {"fmi3SetInt64", SLOT_SET_INT64, 1},                                                      \
    {"fmi3SetUInt64", SLOT_SET_UINT64, 1},                                                    \
    {"fmi3GetString", SLOT_GET_STRING, 1},                                                    \
    {"fmi3SetString", SLOT_SET_STRING, 1},                                                    \
    {"fmi3GetBinary", SLOT_GET_BINARY, 1},                                                    \
    {"fmi3SetBinary", SLOT_SET_BINARY, 1},                                                    \
    {"fmi3EnterEventMode", SLOT_ENTER_EVENT_MODE, 1},                                         \
    {"fmi3UpdateDiscreteStates", SLOT_NEW_DISCRETE_STATES, 1},
/* capabilities an FMU may lack (FMI 3.0 has every binary export them; be lenient) */
#define FMI3_OPTIONAL_ROWS                                                                    \
    {"fmi3GetFMUState", SLOT_GET_STATE, 0},                                                   \
    {"fmi3SetFMUState", SLOT_SET_STATE, 0},                                                   \
    {"fmi3FreeFMUState", SLOT_FREE_STATE, 0},                                                 \
    {"fmi3SerializedFMUStateSize", SLOT_SERIALIZED_STATE_SIZE, 0},                            \
    {"fmi3SerializeFMUState", SLOT_SERIALIZE_STATE, 0},                                       \
    {"fmi3DeserializeFMUState", SLOT_DESERIALIZE_STATE, 0},                                   \
    {"fmi3GetDirectionalDerivative", SLOT_DIRECTIONAL_DERIVATIVE, 0},

static const ssx_fmu_function_row fmi3_functions[] = {
    {"fmi3InstantiateCoSimulation", SLOT_INSTANTIATE, 1},
    FMI3_COMMON_ROWS
    {"fmi3DoStep", SLOT_DO_STEP, 1},
    /* doStep's out-arguments say what FMI 2.0 asks status functions for */
    {"fmi3DoStep", SLOT_GET_TERMINATED, 1},
    {"fmi3DoStep", SLOT_GET_LAST_SUCCESSFUL_TIME, 1},
    {"fmi3EnterStepMode", SLOT_ENTER_STEP_MODE, 1},
    FMI3_OPTIONAL_ROWS
};

/* Model Exchange: the common functions, the ones of the interface instead of fmi3DoStep. */
static const ssx_fmu_function_row fmi3_model_exchange_functions[] = {
    {"fmi3InstantiateModelExchange", SLOT_INSTANTIATE, 1},
    FMI3_COMMON_ROWS
    {"fmi3SetTime", SLOT_SET_TIME, 1},
    {"fmi3SetContinuousStates", SLOT_SET_CONTINUOUS_STATES, 1},
    {"fmi3GetContinuousStates", SLOT_GET_CONTINUOUS_STATES, 1},
    {"fmi3GetContinuousStateDerivatives", SLOT_GET_DERIVATIVES, 1},
    {"fmi3GetEventIndicators", SLOT_GET_EVENT_INDICATORS, 1},
    {"fmi3GetNominalsOfContinuousStates", SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES, 1},
    {"fmi3EnterContinuousTimeMode", SLOT_ENTER_CONTINUOUS_TIME_MODE, 1},
    {"fmi3CompletedIntegratorStep", SLOT_COMPLETED_INTEGRATOR_STEP, 1},
    {"fmi3GetNumberOfContinuousStates", SLOT_GET_NUMBER_OF_CONTINUOUS_STATES, 1},
    {"fmi3GetNumberOfEventIndicators", SLOT_GET_NUMBER_OF_EVENT_INDICATORS, 1},
    FMI3_OPTIONAL_ROWS
};

#define FMI3_NAME(name) "fmi3" #name,
static const char *const fmi3_status_names[] = {SSX_STATUS_NAMES(FMI3_NAME)};

/* Rounds of fmi3UpdateDiscreteStates after initialization before it counts as chattering. */
enum { INITIAL_UPDATE_ROUNDS = 1000 };

static const char *const type_names[SSX_FMI3_TYPE_COUNT] = {
    "Float64", "Float32", "Int8",  "UInt8",  "Int16",  "UInt16",
    "Int32",   "UInt32",  "Int64", "UInt64", "Boolean"};

/* The slot of each type's getter and setter. */
static const ssx_fmu_slot getter[SSX_FMI3_TYPE_COUNT] = {
    SLOT_GET_REAL,  SLOT_GET_FLOAT32, SLOT_GET_INT8,    SLOT_GET_UINT8,
    SLOT_GET_INT16, SLOT_GET_UINT16,  SLOT_GET_INTEGER, SLOT_GET_UINT32,
    SLOT_GET_INT64, SLOT_GET_UINT64,  SLOT_GET_BOOLEAN};
static const ssx_fmu_slot setter[SSX_FMI3_TYPE_COUNT] = {
    SLOT_SET_REAL,  SLOT_SET_FLOAT32, SLOT_SET_INT8,    SLOT_SET_UINT8,
    SLOT_SET_INT16, SLOT_SET_UINT16,  SLOT_SET_INTEGER, SLOT_SET_UINT32,
    SLOT_SET_INT64, SLOT_SET_UINT64,  SLOT_SET_BOOLEAN};

/* The engine port type each FMI 3.0 type is exchanged as. */
static ssx_value_type port_type(ssx_fmi3_type type)
{
    return type <= SSX_FMI3_FLOAT32   ? SSX_REAL
           : type == SSX_FMI3_BOOLEAN ? SSX_BOOLEAN
                                      : SSX_INTEGER;
}

typedef struct {
    unsigned int vr; /* the engine's: the FMU's for a scalar, the element's own in an array */
    unsigned char type;
    const char *name; /* into the context's name pool */
    size_t array;     /* 1 + the index of its array among the context's, 0 for a scalar */
    size_t element;   /* its position in the array (row-major) */
} variable;

/* An FMU array variable: read and written whole, one fmi3Get/Set call per engine call. */
typedef struct {
    unsigned int vr; /* the FMU's */
    unsigned char type;
    size_t size;
    void *start;  /* the start values given at load */
    void *values; /* the values last written, start until then: a write completes with them */
    void *read;   /* the values last read */
    int fresh;    /* read during this engine call */
    int pending;  /* written during this engine call, not yet sent */
} array;

typedef struct {
    fmi3Instance instance; /* the FMU's; NULL until instantiated */
    ssx_fmu *fmu;          /* the environment of log messages */
    variable *variables;   /* sorted by value reference */
    size_t n_variables;
    char *names;
    array *arrays;
    size_t n_arrays;
    int event_mode_used;
    int early_return_allowed;
    /* the experiment, kept for fmi3EnterInitializationMode */
    int tolerance_defined;
    double tolerance;
    double start_time;
    int stop_time_defined;
    double stop_time;
    ssx_step_outcome outcome;
    /* one type's part of a batch: value references, positions in the engine's call, values */
    unsigned int *part_vr;
    size_t *part_at;
    uint64_t *part_values; /* 8 bytes per value hold any numeric type */
    size_t part_capacity;
} fmi3_context;

/* The function in `slot` with its fmi3 type (ISO C converts between function pointer types). */
#define FMI3(fn, slot, type) ((type *)(fn)[slot])

/* ------------------------------------------------------------------ load */

static int by_value_reference(const void *a, const void *b)
{
    unsigned int x = ((const variable *)a)->vr, y = ((const variable *)b)->vr;
    return (x > y) - (x < y);
}

static int put_real(ssx_fmi3_type type, void *values, size_t k, double d);

/* The arrays the elements among `variables` belong to (ctx->variables in the given order),
 * each with its buffers and start values; every element points at its array. */
static int collect_arrays(fmi3_context *ctx, const ssx_fmi3_variables *variables, char *error,
                          size_t error_size)
{
    if (variables->fmu_vr == NULL || variables->element == NULL) {
        snprintf(error, error_size, "array sizes given without value references and elements");
        return -1;
    }
    size_t elements = 0;
    for (size_t i = 0; i < variables->n; ++i) {
        elements += variables->size[i] > 0;
    }
    ctx->arrays = calloc(elements > 0 ? elements : 1, sizeof *ctx->arrays);
    if (ctx->arrays == NULL) {
        snprintf(error, error_size, "out of memory keeping the FMU's arrays");
        return -1;
    }
    for (size_t i = 0; i < variables->n; ++i) {
        size_t size = variables->size[i], element = variables->element[i];
        if (size == 0) {
            continue;
        }
        variable *v = &ctx->variables[i];
        size_t j = ctx->n_arrays;
        while (j > 0 && ctx->arrays[j - 1].vr != variables->fmu_vr[i]) {
            --j;
        }
        if (j == 0) {
            unsigned char *block =
                size <= SIZE_MAX / (3 * sizeof(uint64_t)) ? calloc(3 * size, sizeof(uint64_t))
                                                          : NULL;
            if (block == NULL) {
                snprintf(error, error_size, "out of memory keeping the %zu elements of '%s'",
                         size, v->name);
                return -1;
            }
            /* 8 bytes per element hold any type: start, values and read share one block */
            ctx->arrays[ctx->n_arrays++] = (array){
                .vr = variables->fmu_vr[i],
                .type = v->type,
                .size = size,
                .start = block,
                .values = block + size * sizeof(uint64_t),
                .read = block + 2 * size * sizeof(uint64_t),
            };
            j = ctx->n_arrays;
        }
        array *a = &ctx->arrays[j - 1];
        if (a->size != size || a->type != v->type || element >= size) {
            snprintf(error, error_size,
                     "variable '%s': element %zu of a %zu-element %s array does not fit the "
                     "%zu-element %s array of value reference %u",
                     v->name, element, size, type_names[v->type], a->size, type_names[a->type],
                     a->vr);
            return -1;
        }
        double start = variables->start != NULL ? variables->start[i] : 0.0;
        if (put_real((ssx_fmi3_type)v->type, a->start, element, start) != 0) {
            snprintf(error, error_size, "variable '%s' (%s): start value %.17g does not fit",
                     v->name, type_names[v->type], start);
            return -1;
        }
        v->array = j;
        v->element = element;
    }
    for (size_t j = 0; j < ctx->n_arrays; ++j) {
        memcpy(ctx->arrays[j].values, ctx->arrays[j].start,
               ctx->arrays[j].size * sizeof(uint64_t));
    }
    return 0;
}

/* The load-time facts, into the zeroed context: the type of every value reference the engine
 * gets or sets (copied) and how the FMU is instantiated. Fails when out of memory or when a
 * type is not an ssx_fmi3_type. */
static int prepare(void *context, const ssx_fmu_load_spec *spec, char *error, size_t error_size)
{
    fmi3_context *ctx = context;
    const ssx_fmi3_variables *variables = spec->fmi3_variables;
    size_t n = variables != NULL ? variables->n : 0;
    size_t pool = 0;
    for (size_t i = 0; i < n; ++i) {
        if (variables->type[i] >= SSX_FMI3_TYPE_COUNT) {
            snprintf(error, error_size,
                     "value reference %u: FMI 3.0 type code %d is not an "
                     "ssx_fmi3_type",
                     variables->vr[i], variables->type[i]);
            return -1;
        }
        pool += strlen(variables->name[i] != NULL ? variables->name[i] : "") + 1;
    }
    ctx->variables = calloc(n > 0 ? n : 1, sizeof *ctx->variables);
    ctx->names = malloc(pool > 0 ? pool : 1);
    if (ctx->variables == NULL || ctx->names == NULL) {
        snprintf(error, error_size, "out of memory keeping the FMU's %zu variables", n);
        return -1;
    }
    char *at = ctx->names;
    for (size_t i = 0; i < n; ++i) {
        const char *name = variables->name[i] != NULL ? variables->name[i] : "";
        size_t length = strlen(name) + 1;
        memcpy(at, name, length);
        ctx->variables[i] = (variable){variables->vr[i], variables->type[i], at, 0, 0};
        at += length;
    }
    if (variables != NULL && variables->size != NULL &&
        collect_arrays(ctx, variables, error, error_size) != 0) {
        return -1;
    }
    qsort(ctx->variables, n, sizeof *ctx->variables, by_value_reference);
    ctx->n_variables = n;
    if (variables != NULL) {
        ctx->event_mode_used = variables->event_mode_used != 0;
        ctx->early_return_allowed = variables->early_return_allowed != 0;
    }
    return 0;
}

static void release_context(void *context)
{
    fmi3_context *ctx = context;
    for (size_t i = 0; i < ctx->n_arrays; ++i) {
        free(ctx->arrays[i].start);
    }
    free(ctx->arrays);
    free(ctx->variables);
    free(ctx->names);
    free(ctx->part_vr);
    free(ctx->part_at);
    free(ctx->part_values);
}

/* ------------------------------------------------------------------ messages */

static void say(fmi3_context *ctx, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    ssx_fmu_log(ctx->fmu, format, args);
    va_end(args);
}

static void logger(fmi3InstanceEnvironment environment, fmi3Status status, fmi3String category,
                   fmi3String message)
{
    (void)status;
    (void)category;
    if (environment != NULL && message != NULL) {
        say(environment, "%s", message);
    }
}

/* ------------------------------------------------------------------ life cycle */

static void *instantiate(const ssx_fmu_function *fn, void *context, ssx_fmu *fmu,
                         const char *instance_name, const char *token, const char *resource_path,
                         int logging_on)
{
    fmi3_context *ctx = context;
    ctx->fmu = fmu;
    ctx->outcome = (ssx_step_outcome){0};
    /* the logger's environment is the context, whose first use is to reach the fmu */
    ctx->instance = FMI3(fn, SLOT_INSTANTIATE, fmi3InstantiateCoSimulationTYPE)(
        instance_name, token, resource_path, fmi3False, logging_on ? fmi3True : fmi3False,
        ctx->event_mode_used ? fmi3True : fmi3False,
        ctx->early_return_allowed ? fmi3True : fmi3False, NULL, 0, ctx,
        (fmi3LogMessageCallback)logger, NULL);
    if (ctx->instance == NULL && ctx->event_mode_used) {
        /* Some FMUs declare hasEventMode and then refuse it (the Reference FMUs' Roberts):
         * without event mode the FMU handles its events inside doStep, which FMI 3.0 allows
         * any importer to choose. */
        ctx->event_mode_used = 0;
        ctx->instance = FMI3(fn, SLOT_INSTANTIATE, fmi3InstantiateCoSimulationTYPE)(
            instance_name, token, resource_path, fmi3False, logging_on ? fmi3True : fmi3False,
            fmi3False, ctx->early_return_allowed ? fmi3True : fmi3False, NULL, 0, ctx,
            (fmi3LogMessageCallback)logger, NULL);
    }
    return ctx->instance != NULL ? ctx : NULL;
}

static void free_instance(const ssx_fmu_function *fn, void *instance)
{
    fmi3_context *ctx = instance;
    FMI3(fn, SLOT_FREE_INSTANCE, fmi3FreeInstanceTYPE)(ctx->instance);
    ctx->instance = NULL;
}

static int setup_experiment(const ssx_fmu_function *fn, void *instance, int tolerance_defined,
                            double tolerance, double start_time, int stop_time_defined,
                            double stop_time)
{
    (void)fn;
    fmi3_context *ctx = instance;
    ctx->tolerance_defined = tolerance_defined;
    ctx->tolerance = tolerance;
    ctx->start_time = start_time;
    ctx->stop_time_defined = stop_time_defined;
    ctx->stop_time = stop_time;
    return fmi3OK;
}

static int enter_initialization_mode(const ssx_fmu_function *fn, void *instance)
{
    fmi3_context *ctx = instance;
    return (int)FMI3(fn, SLOT_ENTER_INITIALIZATION_MODE, fmi3EnterInitializationModeTYPE)(
        ctx->instance, ctx->tolerance_defined ? fmi3True : fmi3False, ctx->tolerance,
        ctx->start_time, ctx->stop_time_defined ? fmi3True : fmi3False, ctx->stop_time);
}

static int worse(int a, int b)
{
    return a > b ? a : b;
}

/* With eventModeUsed the instance leaves initialization in event mode: its discrete states are
 * settled at the start time before stepping begins, as part of initializing it. */
static int exit_initialization_mode(const ssx_fmu_function *fn, void *instance)
{
    fmi3_context *ctx = instance;
    int status =
        (int)FMI3(fn, SLOT_EXIT_INITIALIZATION_MODE, fmi3ExitInitializationModeTYPE)(ctx->instance);
    if (!ctx->event_mode_used || status > fmi3Warning) {
        return status;
    }
    fmi3Boolean again = fmi3True;
    for (int round = 0; again; ++round) {
        if (round == INITIAL_UPDATE_ROUNDS) {
            say(ctx,
                "fmi3UpdateDiscreteStates still asked for another round after %d rounds "
                "at the start time %.17g (chattering)",
                INITIAL_UPDATE_ROUNDS, ctx->start_time);
            return fmi3Error;
        }
        fmi3Boolean terminate = fmi3False, nominals = fmi3False, values = fmi3False;
        fmi3Boolean next_defined = fmi3False;
        fmi3Float64 next = 0.0;
        status =
            worse(status,
                  (int)FMI3(fn, SLOT_NEW_DISCRETE_STATES, fmi3UpdateDiscreteStatesTYPE)(
                      ctx->instance, &again, &terminate, &nominals, &values, &next_defined, &next));
        if (status > fmi3Warning) {
            return status;
        }
        if (terminate) {
            say(ctx,
                "the FMU asked to terminate the simulation during initialization "
                "(fmi3UpdateDiscreteStates at t=%.17g)",
                ctx->start_time);
            return fmi3Error;
        }
    }
    return worse(status, (int)FMI3(fn, SLOT_ENTER_STEP_MODE, fmi3EnterStepModeTYPE)(ctx->instance));
}

static int terminate(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI3(fn, SLOT_TERMINATE, fmi3TerminateTYPE)(((fmi3_context *)instance)->instance);
}

static int reset(const ssx_fmu_function *fn, void *instance)
{
    fmi3_context *ctx = instance;
    ctx->outcome = (ssx_step_outcome){0};
    /* the reset FMU holds its start values again */
    for (size_t i = 0; i < ctx->n_arrays; ++i) {
        memcpy(ctx->arrays[i].values, ctx->arrays[i].start,
               ctx->arrays[i].size * sizeof(uint64_t));
    }
    return (int)FMI3(fn, SLOT_RESET, fmi3ResetTYPE)(ctx->instance);
}

/* ------------------------------------------------------------------ values */

static const variable *find(const fmi3_context *ctx, unsigned int vr)
{
    size_t lo = 0, hi = ctx->n_variables;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (ctx->variables[mid].vr < vr) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo < ctx->n_variables && ctx->variables[lo].vr == vr ? &ctx->variables[lo] : NULL;
}

static int reserve_parts(fmi3_context *ctx, size_t n)
{
    if (n <= ctx->part_capacity) {
        return 0;
    }
    unsigned int *vr = realloc(ctx->part_vr, n * sizeof *vr);
    if (vr != NULL) {
        ctx->part_vr = vr;
    }
    size_t *at = realloc(ctx->part_at, n * sizeof *at);
    if (at != NULL) {
        ctx->part_at = at;
    }
    uint64_t *values = realloc(ctx->part_values, n * sizeof *values);
    if (values != NULL) {
        ctx->part_values = values;
    }
    if (vr == NULL || at == NULL || values == NULL) {
        say(ctx, "out of memory batching %zu values", n);
        return -1;
    }
    ctx->part_capacity = n;
    return 0;
}

/* A variable of `type` travels as its own port family, an integer one also as Real. */
static int exchanged_as(ssx_fmi3_type type, ssx_value_type port)
{
    return port_type(type) == port || (port == SSX_REAL && port_type(type) == SSX_INTEGER);
}

/* Every vr is known and may travel as `port`. Returns their type when all are the same
 * scalar type, SSX_FMI3_TYPE_COUNT when they differ or one is an array element, -1 for an
 * unknown or foreign one. */
static int common_type(fmi3_context *ctx, ssx_value_type port, const unsigned int *vr, size_t n)
{
    int common = -1;
    for (size_t i = 0; i < n; ++i) {
        const variable *v = find(ctx, vr[i]);
        if (v == NULL) {
            say(ctx, "value reference %u is not among the variables the FMU was loaded with",
                vr[i]);
            return -1;
        }
        if (!exchanged_as(v->type, port)) {
            say(ctx, "variable '%s' (%s) is not exchanged as this port type", v->name,
                type_names[v->type]);
            return -1;
        }
        common = v->array != 0                        ? SSX_FMI3_TYPE_COUNT
                 : common < 0 || common == v->type ? v->type
                                                      : SSX_FMI3_TYPE_COUNT;
    }
    return common;
}

/* Whether values of `type` pass to `port` unconverted. */
static int direct(int type, ssx_value_type port)
{
    return (type == SSX_FMI3_FLOAT64 && port == SSX_REAL) ||
           (type == SSX_FMI3_INT32 && port == SSX_INTEGER);
}

/* Gathers the scalars of type `type` into the parts; returns how many. */
static size_t gather(fmi3_context *ctx, ssx_fmi3_type type, const unsigned int *vr, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        const variable *v = find(ctx, vr[i]);
        if (v->array == 0 && v->type == type) {
            ctx->part_vr[k] = vr[i];
            ctx->part_at[k++] = i;
        }
    }
    return k;
}

/* One fmi3GetX call of `type` for n value references into `values` (n_values of that type:
 * more than n when one is an array). */
static int get_typed(const ssx_fmu_function *fn, fmi3Instance instance, ssx_fmi3_type type,
                     const unsigned int *vr, size_t n, void *values, size_t n_values)
{
    ssx_fmu_function f = fn[getter[type]];
    switch (type) {
    case SSX_FMI3_FLOAT64:
        return (int)((fmi3GetFloat64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_FLOAT32:
        return (int)((fmi3GetFloat32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT8:
        return (int)((fmi3GetInt8TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT8:
        return (int)((fmi3GetUInt8TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT16:
        return (int)((fmi3GetInt16TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT16:
        return (int)((fmi3GetUInt16TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT32:
        return (int)((fmi3GetInt32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT32:
        return (int)((fmi3GetUInt32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT64:
        return (int)((fmi3GetInt64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT64:
        return (int)((fmi3GetUInt64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_BOOLEAN:
        return (int)((fmi3GetBooleanTYPE *)f)(instance, vr, n, values, n_values);
    default:
        return fmi3Error;
    }
}

static int set_typed(const ssx_fmu_function *fn, fmi3Instance instance, ssx_fmi3_type type,
                     const unsigned int *vr, size_t n, const void *values, size_t n_values)
{
    ssx_fmu_function f = fn[setter[type]];
    switch (type) {
    case SSX_FMI3_FLOAT64:
        return (int)((fmi3SetFloat64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_FLOAT32:
        return (int)((fmi3SetFloat32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT8:
        return (int)((fmi3SetInt8TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT8:
        return (int)((fmi3SetUInt8TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT16:
        return (int)((fmi3SetInt16TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT16:
        return (int)((fmi3SetUInt16TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT32:
        return (int)((fmi3SetInt32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT32:
        return (int)((fmi3SetUInt32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT64:
        return (int)((fmi3SetInt64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT64:
        return (int)((fmi3SetUInt64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_BOOLEAN:
        return (int)((fmi3SetBooleanTYPE *)f)(instance, vr, n, values, n_values);
    default:
        return fmi3Error;
    }
}

/* Element k of an array of integer `type`, widened; unsigned ones above INT64_MAX clamp there
 * (they do not fit an int either way). */
static long long integer_at(ssx_fmi3_type type, const void *values, size_t k)
{
    switch (type) {
    case SSX_FMI3_INT8:
        return ((const int8_t *)values)[k];
    case SSX_FMI3_UINT8:
        return ((const uint8_t *)values)[k];
    case SSX_FMI3_INT16:
        return ((const int16_t *)values)[k];
    case SSX_FMI3_UINT16:
        return ((const uint16_t *)values)[k];
    case SSX_FMI3_INT32:
        return ((const int32_t *)values)[k];
    case SSX_FMI3_UINT32:
        return ((const uint32_t *)values)[k];
    case SSX_FMI3_INT64:
        return ((const int64_t *)values)[k];
    case SSX_FMI3_UINT64: {
        uint64_t u = ((const uint64_t *)values)[k];
        return u > (uint64_t)LLONG_MAX ? LLONG_MAX : (long long)u;
    }
    default:
        return 0;
    }
}

/* The range of integer `type`, within long long. */
static void integer_range(ssx_fmi3_type type, long long *lo, long long *hi)
{
    static const long long bounds[][2] = {
        [SSX_FMI3_INT8] = {INT8_MIN, INT8_MAX},    [SSX_FMI3_UINT8] = {0, UINT8_MAX},
        [SSX_FMI3_INT16] = {INT16_MIN, INT16_MAX}, [SSX_FMI3_UINT16] = {0, UINT16_MAX},
        [SSX_FMI3_INT32] = {INT32_MIN, INT32_MAX}, [SSX_FMI3_UINT32] = {0, UINT32_MAX},
        [SSX_FMI3_INT64] = {INT64_MIN, INT64_MAX}, [SSX_FMI3_UINT64] = {0, LLONG_MAX},
    };
    *lo = bounds[type][0];
    *hi = bounds[type][1];
}

static void put_integer(ssx_fmi3_type type, void *values, size_t k, long long value)
{
    switch (type) {
    case SSX_FMI3_INT8:
        ((int8_t *)values)[k] = (int8_t)value;
        break;
    case SSX_FMI3_UINT8:
        ((uint8_t *)values)[k] = (uint8_t)value;
        break;
    case SSX_FMI3_INT16:
        ((int16_t *)values)[k] = (int16_t)value;
        break;
    case SSX_FMI3_UINT16:
        ((uint16_t *)values)[k] = (uint16_t)value;
        break;
    case SSX_FMI3_INT32:
        ((int32_t *)values)[k] = (int32_t)value;
        break;
    case SSX_FMI3_UINT32:
        ((uint32_t *)values)[k] = (uint32_t)value;
        break;
    case SSX_FMI3_INT64:
        ((int64_t *)values)[k] = (int64_t)value;
        break;
    case SSX_FMI3_UINT64:
        ((uint64_t *)values)[k] = (uint64_t)value;
        break;
    default:
        break;
    }
}

/* Beyond 2^53 in magnitude a double no longer holds every integer: an integer variable
 * exchanged as a Real port carries its value exactly up to there and fails beyond. */
static const double EXACT_INTEGER = 9007199254740992.0;

/* Whether d is a whole number that integer `type` holds and a double carries exactly. */
static int whole_in_range(ssx_fmi3_type type, double d)
{
    long long lo, hi;
    integer_range(type, &lo, &hi);
    double low = lo < -EXACT_INTEGER ? -EXACT_INTEGER : (double)lo;
    double high = hi > EXACT_INTEGER ? EXACT_INTEGER : (double)hi;
    return d >= low && d <= high && (double)(long long)d == d;
}

/* Element k of `values` (of `type`) as a double: the Real port's value of a float or an
 * integer, or of a Boolean (1, 0). */
static double real_at(ssx_fmi3_type type, const void *values, size_t k)
{
    switch (type) {
    case SSX_FMI3_FLOAT64:
        return ((const double *)values)[k];
    case SSX_FMI3_FLOAT32:
        return (double)((const float *)values)[k];
    case SSX_FMI3_BOOLEAN:
        return ((const bool *)values)[k] ? 1.0 : 0.0;
    case SSX_FMI3_UINT64:
        return (double)((const uint64_t *)values)[k];
    default:
        return (double)integer_at(type, values, k);
    }
}

/* Stores d as element k of `values` (of `type`); -1 when an integer type cannot hold it. */
static int put_real(ssx_fmi3_type type, void *values, size_t k, double d)
{
    switch (type) {
    case SSX_FMI3_FLOAT64:
        ((double *)values)[k] = d;
        return 0;
    case SSX_FMI3_FLOAT32:
        ((float *)values)[k] = (float)d;
        return 0;
    case SSX_FMI3_BOOLEAN:
        ((bool *)values)[k] = d != 0.0;
        return 0;
    default:
        if (!whole_in_range(type, d)) {
            return -1;
        }
        put_integer(type, values, k, (long long)d);
        return 0;
    }
}

/* Converts element k of `values` (v's type) into the engine's array `out` of port type `port`
 * at `at`; 0, or -1 when the value does not fit. */
static int take(fmi3_context *ctx, const variable *v, const void *values, size_t k,
                ssx_value_type port, void *out, size_t at)
{
    ssx_fmi3_type type = (ssx_fmi3_type)v->type;
    if (port == SSX_REAL) {
        double value = real_at(type, values, k);
        if (port_type(type) == SSX_INTEGER && !(value >= -EXACT_INTEGER && value <= EXACT_INTEGER)) {
            if (type == SSX_FMI3_UINT64) {
                say(ctx,
                    "variable '%s' (UInt64) holds %llu, beyond 2^53, the largest magnitude "
                    "up to which the engine's Real ports carry integers exactly",
                    v->name, (unsigned long long)((const uint64_t *)values)[k]);
            } else {
                say(ctx,
                    "variable '%s' (%s) holds %lld, beyond 2^53, the largest magnitude up to "
                    "which the engine's Real ports carry integers exactly",
                    v->name, type_names[type], integer_at(type, values, k));
            }
            return -1;
        }
        ((double *)out)[at] = value;
        return 0;
    }
    if (port == SSX_BOOLEAN) {
        ((int *)out)[at] = ((const bool *)values)[k] ? 1 : 0;
        return 0;
    }
    long long value = integer_at(type, values, k);
    if (value < INT_MIN || value > INT_MAX) {
        if (type == SSX_FMI3_UINT64) {
            say(ctx,
                "variable '%s' (UInt64) holds %llu, outside the range of the engine's "
                "Integer ports (%d..%d)",
                v->name, (unsigned long long)((const uint64_t *)values)[k], INT_MIN, INT_MAX);
        } else {
            say(ctx,
                "variable '%s' (%s) holds %lld, outside the range of the engine's Integer "
                "ports (%d..%d)",
                v->name, type_names[type], value, INT_MIN, INT_MAX);
        }
        return -1;
    }
    ((int *)out)[at] = (int)value;
    return 0;
}

/* Converts the engine's value at `at` of `in` into element k of `values` (v's type); -1 when
 * it does not fit the type. */
static int give(fmi3_context *ctx, const variable *v, void *values, size_t k,
                ssx_value_type port, const void *in, size_t at)
{
    ssx_fmi3_type type = (ssx_fmi3_type)v->type;
    if (port == SSX_REAL) {
        double value = ((const double *)in)[at];
        if (put_real(type, values, k, value) != 0) {
            long long lo, hi;
            integer_range(type, &lo, &hi);
            /* the range first: casting a double beyond long long is undefined */
            if (!(value > -EXACT_INTEGER && value < EXACT_INTEGER) ||
                value == (double)(long long)value) {
                say(ctx,
                    "variable '%s' (%s) cannot take %.17g: outside %.17g..%.17g (its range, "
                    "within the 2^53 up to which the engine's Real ports carry integers "
                    "exactly)",
                    v->name, type_names[type], value,
                    lo < -EXACT_INTEGER ? -EXACT_INTEGER : (double)lo,
                    hi > EXACT_INTEGER ? EXACT_INTEGER : (double)hi);
            } else {
                say(ctx, "variable '%s' (%s) cannot take %.17g: not a whole number", v->name,
                    type_names[type], value);
            }
            return -1;
        }
        return 0;
    }
    int value = ((const int *)in)[at];
    if (port == SSX_BOOLEAN) {
        ((bool *)values)[k] = value != 0;
        return 0;
    }
    long long lo, hi;
    integer_range(type, &lo, &hi);
    if (value < lo || value > hi) {
        say(ctx, "variable '%s' (%s) cannot take %d: outside %lld..%lld", v->name,
            type_names[type], value, lo, hi);
        return -1;
    }
    put_integer(type, values, k, value);
    return 0;
}

/* Whether a status (or -1, a value that did not fit) lets the call go on. */
static int usable(int status)
{
    return status == fmi3OK || status == fmi3Warning;
}

static array *array_of(fmi3_context *ctx, const variable *v)
{
    return v->array != 0 ? &ctx->arrays[v->array - 1] : NULL;
}

/* The array elements among vr: each array read whole, once per call. */
static int get_elements(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                        const unsigned int *vr, size_t n, void *out)
{
    int result = fmi3OK;
    for (size_t i = 0; i < n && usable(result); ++i) {
        const variable *v = find(ctx, vr[i]);
        array *a = array_of(ctx, v);
        if (a == NULL) {
            continue;
        }
        if (!a->fresh) {
            result = worse(result, get_typed(fn, ctx->instance, (ssx_fmi3_type)a->type, &a->vr,
                                             1, a->read, a->size));
            a->fresh = 1;
        }
        if (usable(result) && take(ctx, v, a->read, v->element, port, out, i) != 0) {
            result = -1;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        array *a = array_of(ctx, find(ctx, vr[i]));
        if (a != NULL) {
            a->fresh = 0;
        }
    }
    return result;
}

/* The array elements among vr: each array written whole, once per call, its other elements
 * as last written (their start values until then). */
static int set_elements(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                        const unsigned int *vr, size_t n, const void *in)
{
    int result = fmi3OK;
    for (size_t i = 0; i < n && result == fmi3OK; ++i) {
        const variable *v = find(ctx, vr[i]);
        array *a = array_of(ctx, v);
        if (a != NULL) {
            result = give(ctx, v, a->values, v->element, port, in, i);
            a->pending = 1;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        array *a = array_of(ctx, find(ctx, vr[i]));
        if (a != NULL && a->pending) {
            a->pending = 0;
            if (usable(result)) {
                result = worse(result, set_typed(fn, ctx->instance, (ssx_fmi3_type)a->type,
                                                 &a->vr, 1, a->values, a->size));
            }
        }
    }
    return result;
}

/* The engine's get of `port` type: one fmi3 call per FMI 3.0 type among the scalars of vr,
 * one per array among its elements. */
static int get_values(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                      const unsigned int *vr, size_t n, void *out)
{
    int common = common_type(ctx, port, vr, n);
    if (common < 0) {
        return -1;
    }
    /* the usual case: nothing to convert */
    if (direct(common, port)) {
        return get_typed(fn, ctx->instance, (ssx_fmi3_type)common, vr, n, out, n);
    }
    if (reserve_parts(ctx, n) != 0) {
        return -1;
    }
    int worst = fmi3OK;
    for (int type = 0; type < SSX_FMI3_TYPE_COUNT; ++type) {
        if (!exchanged_as((ssx_fmi3_type)type, port)) {
            continue;
        }
        size_t m = gather(ctx, (ssx_fmi3_type)type, vr, n);
        if (m == 0) {
            continue;
        }
        int status = get_typed(fn, ctx->instance, (ssx_fmi3_type)type, ctx->part_vr, m,
                               ctx->part_values, m);
        worst = worse(worst, status);
        if (status > fmi3Warning) {
            return status;
        }
        for (size_t k = 0; k < m; ++k) {
            if (take(ctx, find(ctx, ctx->part_vr[k]), ctx->part_values, k, port, out,
                     ctx->part_at[k]) != 0) {
                return -1;
            }
        }
    }
    int status = get_elements(fn, ctx, port, vr, n, out);
    return status < 0 ? status : worse(worst, status);
}

static int set_values(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                      const unsigned int *vr, size_t n, const void *in)
{
    int common = common_type(ctx, port, vr, n);
    if (common < 0) {
        return -1;
    }
    if (direct(common, port)) {
        return set_typed(fn, ctx->instance, (ssx_fmi3_type)common, vr, n, in, n);
    }
    if (reserve_parts(ctx, n) != 0) {
        return -1;
    }
    int worst = fmi3OK;
    for (int type = 0; type < SSX_FMI3_TYPE_COUNT; ++type) {
        if (!exchanged_as((ssx_fmi3_type)type, port)) {
            continue;
        }
        size_t m = gather(ctx, (ssx_fmi3_type)type, vr, n);
        if (m == 0) {
            continue;
        }
        for (size_t k = 0; k < m; ++k) {
            if (give(ctx, find(ctx, ctx->part_vr[k]), ctx->part_values, k, port, in,
                     ctx->part_at[k]) != 0) {
                return -1;
            }
        }
        int status = set_typed(fn, ctx->instance, (ssx_fmi3_type)type, ctx->part_vr, m,
                               ctx->part_values, m);
        worst = worse(worst, status);
        if (status > fmi3Warning) {
            return status;
        }
    }
    int status = set_elements(fn, ctx, port, vr, n, in);
    return status < 0 ? status : worse(worst, status);
}

static int get_real(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    double *values)
{
    return get_values(fn, instance, SSX_REAL, vr, n, values);
}

static int get_integer(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                       int *values)
{
    return get_values(fn, instance, SSX_INTEGER, vr, n, values);
}

static int get_boolean(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                       int *values)
{
    return get_values(fn, instance, SSX_BOOLEAN, vr, n, values);
}

static int set_real(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    const double *values)
{
    return set_values(fn, instance, SSX_REAL, vr, n, values);
}

static int set_integer(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                       const int *values)
{
    return set_values(fn, instance, SSX_INTEGER, vr, n, values);
}

static int set_boolean(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                       const int *values)
{
    return set_values(fn, instance, SSX_BOOLEAN, vr, n, values);
}

static int get_string(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                      const char **values)
{
    return (int)FMI3(fn, SLOT_GET_STRING, fmi3GetStringTYPE)(((fmi3_context *)instance)->instance,
                                                             vr, n, values, n);
}

static int set_string(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                      const char *const *values)
{
    return (int)FMI3(fn, SLOT_SET_STRING, fmi3SetStringTYPE)(((fmi3_context *)instance)->instance,
                                                             vr, n, values, n);
}

static int get_binary(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                      size_t *sizes, const unsigned char **values)
{
    return (int)FMI3(fn, SLOT_GET_BINARY, fmi3GetBinaryTYPE)(((fmi3_context *)instance)->instance,
                                                             vr, n, sizes, values, n);
}

static int set_binary(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                      const size_t *sizes, const unsigned char *const *values)
{
    return (int)FMI3(fn, SLOT_SET_BINARY, fmi3SetBinaryTYPE)(((fmi3_context *)instance)->instance,
                                                             vr, n, sizes, values, n);
}

static const char *variable_name(const void *context, unsigned int vr)
{
    const variable *v = find(context, vr);
    return v != NULL ? v->name : NULL;
}

/* ------------------------------------------------------------------ stepping and events */

static int do_step(const ssx_fmu_function *fn, void *instance, double t, double h,
                   int no_set_state_prior)
{
    fmi3_context *ctx = instance;
    fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
    fmi3Float64 reached = t;
    int status = (int)FMI3(fn, SLOT_DO_STEP, fmi3DoStepTYPE)(
        ctx->instance, t, h, no_set_state_prior ? fmi3True : fmi3False, &event, &terminate, &early,
        &reached);
    ctx->outcome = (ssx_step_outcome){
        .reported = 1,
        .event_handling_needed = ctx->event_mode_used && event,
        .terminate_simulation = terminate != fmi3False,
        .early_return = ctx->early_return_allowed && early,
        .last_successful_time = reached,
    };
    return status;
}

static void step_outcome(void *instance, ssx_step_outcome *outcome)
{
    *outcome = ((const fmi3_context *)instance)->outcome;
}

static int get_terminated(const ssx_fmu_function *fn, void *instance, int *terminated)
{
    (void)fn;
    *terminated = ((const fmi3_context *)instance)->outcome.terminate_simulation;
    return fmi3OK;
}

static int get_last_successful_time(const ssx_fmu_function *fn, void *instance, double *time)
{
    (void)fn;
    *time = ((const fmi3_context *)instance)->outcome.last_successful_time;
    return fmi3OK;
}

static int enter_event_mode(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI3(fn, SLOT_ENTER_EVENT_MODE,
                     fmi3EnterEventModeTYPE)(((fmi3_context *)instance)->instance);
}

static int new_discrete_states(const ssx_fmu_function *fn, void *instance, ssx_fmu_event_info *info)
{
    fmi3Boolean again = fmi3False, terminate = fmi3False, nominals = fmi3False;
    fmi3Boolean values = fmi3False, next_defined = fmi3False;
    fmi3Float64 next = 0.0;
    int status = (int)FMI3(fn, SLOT_NEW_DISCRETE_STATES, fmi3UpdateDiscreteStatesTYPE)(
        ((fmi3_context *)instance)->instance, &again, &terminate, &nominals, &values, &next_defined,
        &next);
    *info = (ssx_fmu_event_info){
        .new_discrete_states_needed = again != fmi3False,
        .terminate_simulation = terminate != fmi3False,
        .nominals_changed = nominals != fmi3False,
        .values_changed = values != fmi3False,
        .next_event_time_defined = next_defined != fmi3False,
        .next_event_time = next,
    };
    return status;
}

static int enter_step_mode(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI3(fn, SLOT_ENTER_STEP_MODE,
                     fmi3EnterStepModeTYPE)(((fmi3_context *)instance)->instance);
}

/* ------------------------------------------------------------------ states and derivatives */

static int get_state(const ssx_fmu_function *fn, void *instance, void **state)
{
    return (int)FMI3(fn, SLOT_GET_STATE, fmi3GetFMUStateTYPE)(((fmi3_context *)instance)->instance,
                                                              state);
}

static int set_state(const ssx_fmu_function *fn, void *instance, void *state)
{
    fmi3_context *ctx = instance;
    /* the restored instance has not stepped yet: no step's news apply to it */
    ctx->outcome = (ssx_step_outcome){0};
    return (int)FMI3(fn, SLOT_SET_STATE, fmi3SetFMUStateTYPE)(ctx->instance, state);
}

static int free_state(const ssx_fmu_function *fn, void *instance, void **state)
{
    return (int)FMI3(fn, SLOT_FREE_STATE,
                     fmi3FreeFMUStateTYPE)(((fmi3_context *)instance)->instance, state);
}

static int serialized_state_size(const ssx_fmu_function *fn, void *instance, void *state,
                                 size_t *size)
{
    return (int)FMI3(fn, SLOT_SERIALIZED_STATE_SIZE, fmi3SerializedFMUStateSizeTYPE)(
        ((fmi3_context *)instance)->instance, state, size);
}

static int serialize_state(const ssx_fmu_function *fn, void *instance, void *state, char *bytes,
                           size_t size)
{
    return (int)FMI3(fn, SLOT_SERIALIZE_STATE, fmi3SerializeFMUStateTYPE)(
        ((fmi3_context *)instance)->instance, state, (fmi3Byte *)bytes, size);
}

static int deserialize_state(const ssx_fmu_function *fn, void *instance, const char *bytes,
                             size_t size, void **state)
{
    return (int)FMI3(fn, SLOT_DESERIALIZE_STATE, fmi3DeserializeFMUStateTYPE)(
        ((fmi3_context *)instance)->instance, (const fmi3Byte *)bytes, size, state);
}

static int directional_derivative(const ssx_fmu_function *fn, void *instance,
                                  const unsigned int *unknowns, size_t n_unknowns,
                                  const unsigned int *knowns, size_t n_knowns,
                                  const double *dv_known, double *dv_unknown)
{
    return (int)FMI3(fn, SLOT_DIRECTIONAL_DERIVATIVE, fmi3GetDirectionalDerivativeTYPE)(
        ((fmi3_context *)instance)->instance, unknowns, n_unknowns, knowns, n_knowns, dv_known,
        n_knowns, dv_unknown, n_unknowns);
}

/* ------------------------------------------------------------------ Model Exchange */

static void *instantiate_model_exchange(const ssx_fmu_function *fn, void *context, ssx_fmu *fmu,
                                        const char *instance_name, const char *token,
                                        const char *resource_path, int logging_on)
{
    fmi3_context *ctx = context;
    ctx->fmu = fmu;
    ctx->outcome = (ssx_step_outcome){0};
    ctx->instance = FMI3(fn, SLOT_INSTANTIATE, fmi3InstantiateModelExchangeTYPE)(
        instance_name, token, resource_path, fmi3False, logging_on ? fmi3True : fmi3False, ctx,
        (fmi3LogMessageCallback)logger);
    return ctx->instance != NULL ? ctx : NULL;
}

/* The instance leaves initialization in event mode; the engine's Model Exchange component
 * runs the event iteration that follows, as for FMI 2.0. */
static int exit_initialization_mode_model_exchange(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI3(fn, SLOT_EXIT_INITIALIZATION_MODE, fmi3ExitInitializationModeTYPE)(
        ((fmi3_context *)instance)->instance);
}

static int set_time(const ssx_fmu_function *fn, void *instance, double time)
{
    return (int)FMI3(fn, SLOT_SET_TIME, fmi3SetTimeTYPE)(((fmi3_context *)instance)->instance,
                                                         time);
}

static int set_continuous_states(const ssx_fmu_function *fn, void *instance, const double *x,
                                 size_t nx)
{
    return (int)FMI3(fn, SLOT_SET_CONTINUOUS_STATES, fmi3SetContinuousStatesTYPE)(
        ((fmi3_context *)instance)->instance, x, nx);
}

static int get_continuous_states(const ssx_fmu_function *fn, void *instance, double *x,
                                 size_t nx)
{
    return (int)FMI3(fn, SLOT_GET_CONTINUOUS_STATES, fmi3GetContinuousStatesTYPE)(
        ((fmi3_context *)instance)->instance, x, nx);
}

static int get_derivatives(const ssx_fmu_function *fn, void *instance, double *dx, size_t nx)
{
    return (int)FMI3(fn, SLOT_GET_DERIVATIVES, fmi3GetContinuousStateDerivativesTYPE)(
        ((fmi3_context *)instance)->instance, dx, nx);
}

static int get_event_indicators(const ssx_fmu_function *fn, void *instance, double *z,
                                size_t nz)
{
    return (int)FMI3(fn, SLOT_GET_EVENT_INDICATORS, fmi3GetEventIndicatorsTYPE)(
        ((fmi3_context *)instance)->instance, z, nz);
}

static int get_nominals_of_continuous_states(const ssx_fmu_function *fn, void *instance,
                                             double *nominals, size_t nx)
{
    return (int)FMI3(fn, SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES,
                     fmi3GetNominalsOfContinuousStatesTYPE)(((fmi3_context *)instance)->instance,
                                                            nominals, nx);
}

static int enter_continuous_time_mode(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI3(fn, SLOT_ENTER_CONTINUOUS_TIME_MODE, fmi3EnterContinuousTimeModeTYPE)(
        ((fmi3_context *)instance)->instance);
}

static int completed_integrator_step(const ssx_fmu_function *fn, void *instance,
                                     int no_set_state_prior, int *enter_event_mode,
                                     int *terminate_simulation)
{
    fmi3Boolean enter = fmi3False, terminate = fmi3False;
    int status = (int)FMI3(fn, SLOT_COMPLETED_INTEGRATOR_STEP, fmi3CompletedIntegratorStepTYPE)(
        ((fmi3_context *)instance)->instance, no_set_state_prior ? fmi3True : fmi3False, &enter,
        &terminate);
    *enter_event_mode = enter != fmi3False;
    *terminate_simulation = terminate != fmi3False;
    return status;
}

static int get_number_of_continuous_states(const ssx_fmu_function *fn, void *instance,
                                           size_t *n)
{
    return (int)FMI3(fn, SLOT_GET_NUMBER_OF_CONTINUOUS_STATES,
                     fmi3GetNumberOfContinuousStatesTYPE)(((fmi3_context *)instance)->instance, n);
}

static int get_number_of_event_indicators(const ssx_fmu_function *fn, void *instance, size_t *n)
{
    return (int)FMI3(fn, SLOT_GET_NUMBER_OF_EVENT_INDICATORS,
                     fmi3GetNumberOfEventIndicatorsTYPE)(((fmi3_context *)instance)->instance, n);
}

/* The adapters both interfaces share. */
#define FMI3_ADAPTERS                                                                         \
    .version = "FMI 3.0", .status_names = fmi3_status_names,                                  \
    .context_size = sizeof(fmi3_context), .free_instance = free_instance,                     \
    .setup_experiment = setup_experiment,                                                     \
    .enter_initialization_mode = enter_initialization_mode, .terminate = terminate,           \
    .reset = reset, .get_real = get_real, .get_integer = get_integer,                         \
    .get_boolean = get_boolean, .set_real = set_real, .set_integer = set_integer,             \
    .set_boolean = set_boolean, .get_state = get_state, .set_state = set_state,               \
    .free_state = free_state, .serialized_state_size = serialized_state_size,                 \
    .serialize_state = serialize_state, .deserialize_state = deserialize_state,               \
    .directional_derivative = directional_derivative, .get_string = get_string,               \
    .set_string = set_string, .get_binary = get_binary, .set_binary = set_binary,             \
    .enter_event_mode = enter_event_mode, .new_discrete_states = new_discrete_states,         \
    .variable_name = variable_name, .prepare = prepare, .release_context = release_context

const ssx_fmu_backend ssx_fmi3_model_exchange_backend = {
    FMI3_ADAPTERS,
    .standard = "FMI 3.0 Model Exchange",
    .interface = SSX_MODEL_EXCHANGE,
    .functions = fmi3_model_exchange_functions,
    .n_functions = sizeof fmi3_model_exchange_functions / sizeof fmi3_model_exchange_functions[0],
    .instantiate = instantiate_model_exchange,
    .exit_initialization_mode = exit_initialization_mode_model_exchange,
    .set_time = set_time,
    .set_continuous_states = set_continuous_states,
    .get_continuous_states = get_continuous_states,
    .get_derivatives = get_derivatives,
    .get_event_indicators = get_event_indicators,
    .get_nominals_of_continuous_states = get_nominals_of_continuous_states,
    .enter_continuous_time_mode = enter_continuous_time_mode,
    .completed_integrator_step = completed_integrator_step,
    .get_number_of_continuous_states = get_number_of_continuous_states,
    .get_number_of_event_indicators = get_number_of_event_indicators,
};

const ssx_fmu_backend ssx_fmi3_backend = {
    FMI3_ADAPTERS,
    .standard = "FMI 3.0 Co-Simulation",
    .interface = SSX_CO_SIMULATION,
    .functions = fmi3_functions,
    .n_functions = sizeof fmi3_functions / sizeof fmi3_functions[0],
    .instantiate = instantiate,
    .exit_initialization_mode = exit_initialization_mode,
    .do_step = do_step,
    .get_terminated = get_terminated,
    .get_last_successful_time = get_last_successful_time,
    .enter_step_mode = enter_step_mode,
    .step_outcome = step_outcome,
};
