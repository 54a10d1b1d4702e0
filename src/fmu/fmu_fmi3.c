/* The FMI 3.0 back-ends of the FMU binding, Co-Simulation, Model Exchange and Scheduled
 * Execution: the fmi3 functions, which of them a binary must export for each interface, and
 * adapters that call each with its fmi3 type.
 *
 * The engine speaks in three port types; FMI 3.0 has eleven numeric ones: the value table
 * (fmu_fmi3_values.c) turns one engine call into one fmi3 call per FMI 3.0 type met.
 *
 * FMI 3.0 passes the experiment to fmi3EnterInitializationMode and returns doStep's news in
 * out-arguments: the instance the binding holds is this back-end's context, which keeps both
 * beside the FMU's own instance. */
#include "fmu_fmi3_context.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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
    {"fmi3SetClock", SLOT_SET_CLOCK, 1},
    /* needed only when the FMU has output clocks */
    {"fmi3GetClock", SLOT_GET_CLOCK, 0},
    /* needed only when the FMU has countdown clocks */
    {"fmi3GetIntervalDecimal", SLOT_GET_INTERVAL, 0},
    {"fmi3GetOutputDerivatives", SLOT_GET_OUTPUT_DERIVATIVES, 0},
    /* input derivatives move the intermediate inputs within fmi3DoStep */
    {"fmi3DoStep", SLOT_SET_INPUT_DERIVATIVES, 1},
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
    /* needed only when the FMU has clocks the engine ticks */
    {"fmi3SetClock", SLOT_SET_CLOCK, 0},
    FMI3_OPTIONAL_ROWS
};

#define FMI3_NAME(name) "fmi3" #name,
static const char *const fmi3_status_names[] = {SSX_STATUS_NAMES(FMI3_NAME)};

/* Rounds of fmi3UpdateDiscreteStates after initialization before it counts as chattering. */
enum { INITIAL_UPDATE_ROUNDS = 1000 };

/* The load spec's type table (ssx_fmi3_prepare) */
static int prepare(void *context, const ssx_fmu_load_spec *spec, char *error, size_t error_size)
{
    return ssx_fmi3_prepare(context, spec->fmi3_variables, error, error_size);
}

static void release_context(void *context)
{
    fmi3_values_free(context);
}

/* ------------------------------------------------------------------ messages */

static void logger(fmi3InstanceEnvironment environment, fmi3Status status, fmi3String category,
                   fmi3String message)
{
    (void)status;
    (void)category;
    /* FMI 3.0's message is text, no format; the environment is checked, never read */
    if (message != NULL) {
        ssx_fmu_environment_log(ssx_fmu_environment_claimed(environment), message);
    }
}

/* ------------------------------------------------------------------ life cycle */

/* Intermediate update: inside a step with moving inputs, the FMU asks for them at `time`. */
static void answer_intermediate_update(fmi3InstanceEnvironment environment, fmi3Float64 time,
                                       fmi3Boolean set_requested, fmi3Boolean get_allowed,
                                       fmi3Boolean step_finished, fmi3Boolean can_return_early,
                                       fmi3Boolean *early_return_requested,
                                       fmi3Float64 *early_return_time)
{
    (void)get_allowed, (void)step_finished, (void)can_return_early, (void)early_return_time;
    if (early_return_requested != NULL) {
        *early_return_requested = fmi3False;
    }
    /* an environment not the one handed to the FMU being called is never read through */
    fmi3_context *ctx = ssx_fmu_environment_claimed(environment) != NULL ? environment : NULL;
    if (!set_requested || ctx == NULL || !ctx->moving) {
        return;
    }
    size_t n = ctx->n_intermediate;
    const double *base = ctx->intermediate_base, *first = base + n, *second = first + n;
    double *values = (double *)second + n;
    double tau = time - ctx->step_start;
    for (size_t j = 0; j < n; ++j) {
        values[j] = base[j] + tau * (first[j] + 0.5 * tau * second[j]);
    }
    /* a refusal shows in the step's own status and log */
    (void)FMI3(ctx->fn, SLOT_SET_REAL, fmi3SetFloat64TYPE)(ctx->instance, ctx->intermediate_vr,
                                                           n, values, n);
}

/* No countdown clock has a tick planned: the instance announced none yet. */
static void forget_countdown_plan(fmi3_context *ctx)
{
    for (size_t i = 0; i < ctx->n_countdown_clocks; ++i) {
        ctx->countdown_next[i] = INFINITY;
    }
}

static void *instantiate(const ssx_fmu_function *fn, void *context, ssx_fmu_environment *environment,
                         const char *instance_name, const char *token, const char *resource_path,
                         int logging_on)
{
    fmi3_context *ctx = context;
    ctx->environment = environment;
    environment->handed = ctx;
    ctx->fn = fn;
    ctx->outcome = (fmu_step_outcome){0};
    forget_countdown_plan(ctx);
    size_t n_moving = ctx->n_intermediate;
    fmi3IntermediateUpdateCallback update = n_moving > 0 ? answer_intermediate_update : NULL;
    /* the logger's environment is the context, whose first use is to reach the FMU's
     * environment */
    ctx->instance = FMI3(fn, SLOT_INSTANTIATE, fmi3InstantiateCoSimulationTYPE)(
        instance_name, token, resource_path, fmi3False, logging_on ? fmi3True : fmi3False,
        ctx->event_mode_used ? fmi3True : fmi3False,
        ctx->early_return_allowed ? fmi3True : fmi3False, ctx->intermediate_vr, n_moving, ctx,
        (fmi3LogMessageCallback)logger, update);
    if (ctx->instance == NULL && ctx->event_mode_used) {
        /* Some FMUs declare hasEventMode and then refuse it (the Reference FMUs' Roberts):
         * without event mode the FMU handles its events inside doStep, which FMI 3.0 allows
         * any importer to choose. */
        ctx->event_mode_used = 0;
        ctx->instance = FMI3(fn, SLOT_INSTANTIATE, fmi3InstantiateCoSimulationTYPE)(
            instance_name, token, resource_path, fmi3False, logging_on ? fmi3True : fmi3False,
            fmi3False, ctx->early_return_allowed ? fmi3True : fmi3False, ctx->intermediate_vr,
            n_moving, ctx, (fmi3LogMessageCallback)logger, update);
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

static int tick_clocks(const ssx_fmu_function *fn, void *instance, double t);
static int plan_clocks(const ssx_fmu_function *fn, void *instance, double t);

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
    /* the clocks that tick at the start time tick as the instance leaves initialization */
    status = worse_status(status, tick_clocks(fn, ctx, ctx->start_time));
    if (status > fmi3Warning) {
        return status;
    }
    fmi3Boolean again = fmi3True;
    for (int round = 0; again; ++round) {
        if (round == INITIAL_UPDATE_ROUNDS) {
            fmi3_say(ctx,
                "fmi3UpdateDiscreteStates still asked for another round after %d rounds "
                "at the start time %.17g (chattering)",
                INITIAL_UPDATE_ROUNDS, ctx->start_time);
            return fmi3Error;
        }
        fmi3Boolean terminate = fmi3False, nominals = fmi3False, values = fmi3False;
        fmi3Boolean next_defined = fmi3False;
        fmi3Float64 next = 0.0;
        status =
            worse_status(status,
                  (int)FMI3(fn, SLOT_NEW_DISCRETE_STATES, fmi3UpdateDiscreteStatesTYPE)(
                      ctx->instance, &again, &terminate, &nominals, &values, &next_defined, &next));
        if (status > fmi3Warning) {
            return status;
        }
        if (terminate) {
            fmi3_say(ctx,
                "the FMU asked to terminate the simulation during initialization "
                "(fmi3UpdateDiscreteStates at t=%.17g)",
                ctx->start_time);
            return fmi3Error;
        }
    }
    status = worse_status(status, plan_clocks(fn, ctx, ctx->start_time));
    if (status > fmi3Warning) {
        return status;
    }
    return worse_status(status, (int)FMI3(fn, SLOT_ENTER_STEP_MODE, fmi3EnterStepModeTYPE)(ctx->instance));
}

static int terminate(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI3(fn, SLOT_TERMINATE, fmi3TerminateTYPE)(((fmi3_context *)instance)->instance);
}

static int reset(const ssx_fmu_function *fn, void *instance)
{
    fmi3_context *ctx = instance;
    /* the reset FMU holds its start values again, and has announced no countdown */
    fmi3_values_reset(ctx);
    forget_countdown_plan(ctx);
    return (int)FMI3(fn, SLOT_RESET, fmi3ResetTYPE)(ctx->instance);
}


static int get_real(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    double *values)
{
    return fmi3_get_values(fn, instance, SSX_REAL, vr, n, values);
}

static int get_integer(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                       int *values)
{
    return fmi3_get_values(fn, instance, SSX_INTEGER, vr, n, values);
}

static int get_boolean(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                       int *values)
{
    return fmi3_get_values(fn, instance, SSX_BOOLEAN, vr, n, values);
}

static int set_real(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    const double *values)
{
    return fmi3_set_values(fn, instance, SSX_REAL, vr, n, values);
}

static int set_integer(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                       const int *values)
{
    return fmi3_set_values(fn, instance, SSX_INTEGER, vr, n, values);
}

static int set_boolean(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                       const int *values)
{
    return fmi3_set_values(fn, instance, SSX_BOOLEAN, vr, n, values);
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
    fmi3_context *ctx = instance;
    int status = (int)FMI3(fn, SLOT_GET_BINARY, fmi3GetBinaryTYPE)(ctx->instance, vr, n, sizes,
                                                                   values, n);
    for (size_t k = 0; status <= fmi3Warning && k < n; ++k) {
        if (values[k] == NULL && sizes[k] != 0) {
            /* the caller would read sizes[k] bytes from address 0 on: never hand that on */
            const char *name = fmi3_variable_name(ctx, vr[k]);
            fmi3_say(ctx, "fmi3GetBinary returned no data (NULL) with a size of %zu bytes for %s "
                     "(value reference %u)", sizes[k], name != NULL ? name : "a variable", vr[k]);
            return fmi3Error;
        }
    }
    return status;
}

static int set_binary(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                      const size_t *sizes, const unsigned char *const *values)
{
    return (int)FMI3(fn, SLOT_SET_BINARY, fmi3SetBinaryTYPE)(((fmi3_context *)instance)->instance,
                                                             vr, n, sizes, values, n);
}

static const char *variable_name(const void *context, unsigned int vr)
{
    return fmi3_variable_name(context, vr);
}

/* ------------------------------------------------------------------ stepping and events */

/* FMI 3.0 has no input derivatives: the derivatives given for the intermediate inputs move
 * them in the next step, through intermediate update. */
static int set_input_derivatives(const ssx_fmu_function *fn, void *instance,
                                 const unsigned int *vr, size_t n, const int *order,
                                 const double *values)
{
    (void)fn;
    fmi3_context *ctx = instance;
    size_t m = ctx->n_intermediate;
    for (size_t i = 0; i < n; ++i) {
        size_t j = 0;
        while (j < m && ctx->intermediate_vr[j] != vr[i]) {
            ++j;
        }
        if (j == m || order[i] < 1 || order[i] > 2) {
            return fmi3Error; /* not an intermediate input, or no such order */
        }
        ctx->intermediate_base[(size_t)order[i] * m + j] = values[i];
    }
    return fmi3OK;
}

/* Moving inputs start the step from the values the FMU holds. */
static int start_moving(const ssx_fmu_function *fn, fmi3_context *ctx, double t)
{
    size_t m = ctx->n_intermediate;
    int any = 0;
    for (size_t j = m; j < 3 * m; ++j) {
        any |= ctx->intermediate_base[j] != 0.0;
    }
    if (!any) {
        return fmi3OK;
    }
    int status = (int)FMI3(fn, SLOT_GET_REAL, fmi3GetFloat64TYPE)(
        ctx->instance, ctx->intermediate_vr, m, ctx->intermediate_base, m);
    ctx->moving = status <= fmi3Warning;
    ctx->step_start = t;
    return status;
}

/* Two clock instants closer than this (relative to the period) are one: t + h of the engine's
 * grid rounds. */
#define CLOCK_INSTANT_CLOSENESS 1e-9

/* Whether clock i ticks at t: t is start + shift + k period for some k >= 0. */
static int ticks_at(const fmi3_context *ctx, size_t i, double t)
{
    double base = ctx->start_time + ctx->clock_shift[i], period = ctx->clock_period[i];
    double k = nearbyint((t - base) / period);
    return k >= 0.0 && fabs(base + k * period - t) <= CLOCK_INSTANT_CLOSENESS * period;
}

/* Two instants closer than this are one tick of countdown clock i (relative to its interval). */
static double countdown_closeness(const fmi3_context *ctx, size_t i)
{
    return CLOCK_INSTANT_CLOSENESS * ctx->countdown_interval[i];
}

/* Whether the tick at `tick` is the instant t (the grid's t + h rounds). */
static int ticks_near(const fmi3_context *ctx, double tick, double t)
{
    for (size_t i = 0; i < ctx->n_clocks; ++i) {
        if (fabs(tick - t) <= CLOCK_INSTANT_CLOSENESS * ctx->clock_period[i]) {
            return 1;
        }
    }
    for (size_t i = 0; i < ctx->n_countdown_clocks; ++i) {
        if (fabs(tick - t) <= countdown_closeness(ctx, i)) {
            return 1;
        }
    }
    return 0;
}

/* The first tick of any clock after t (not at t), INFINITY without clocks. */
static double next_tick_after(const fmi3_context *ctx, double t)
{
    double next = INFINITY;
    for (size_t i = 0; i < ctx->n_clocks; ++i) {
        double base = ctx->start_time + ctx->clock_shift[i], period = ctx->clock_period[i];
        double k = t < base ? 0.0 : floor((t - base) / period) + 1.0;
        double tick = base + k * period;
        if (tick <= t + CLOCK_INSTANT_CLOSENESS * period) {
            tick += period;
        }
        next = fmin(next, tick);
    }
    for (size_t i = 0; i < ctx->n_countdown_clocks; ++i) {
        if (ctx->countdown_next[i] > t + countdown_closeness(ctx, i)) {
            next = fmin(next, ctx->countdown_next[i]);
        }
    }
    return next;
}

/* In event mode at t: the countdown clocks planned for t tick (fmi3SetClock; none: nothing to
 * call); each waits for its next interval, or when it repeats, ticks again one interval on. */
static int tick_countdown_clocks(const ssx_fmu_function *fn, fmi3_context *ctx, double t)
{
    size_t n = 0;
    for (size_t i = 0; i < ctx->n_countdown_clocks; ++i) {
        int due = fabs(ctx->countdown_next[i] - t) <= countdown_closeness(ctx, i);
        ctx->countdown_active[i] = due ? fmi3True : fmi3False;
        if (due) {
            ctx->countdown_next[i] =
                ctx->countdown_repeats[i] ? t + ctx->countdown_interval[i] : INFINITY;
            ++n;
        }
    }
    if (n == 0) {
        return fmi3OK;
    }
    return (int)FMI3(fn, SLOT_SET_CLOCK, fmi3SetClockTYPE)(
        ctx->instance, ctx->countdown_clock_vr, ctx->n_countdown_clocks, ctx->countdown_active);
}

static double next_clock_tick(const void *instance, double t)
{
    return next_tick_after(instance, t);
}

/* In event mode at t: fmi3SetClock on the clocks that tick at t (none: nothing to call). */
static int tick_clocks(const ssx_fmu_function *fn, void *instance, double t)
{
    fmi3_context *ctx = instance;
    size_t n = 0;
    for (size_t i = 0; i < ctx->n_clocks; ++i) {
        ctx->clock_active[i] = ticks_at(ctx, i, t) ? fmi3True : fmi3False;
        n += ctx->clock_active[i] != fmi3False;
    }
    int status = n == 0 ? fmi3OK
                        : (int)FMI3(fn, SLOT_SET_CLOCK, fmi3SetClockTYPE)(
                              ctx->instance, ctx->clock_vr, ctx->n_clocks, ctx->clock_active);
    if (status > fmi3Warning) {
        return status;
    }
    return worse_status(status, tick_countdown_clocks(fn, ctx, t));
}

/* In Initialization or Event Mode at t: the countdown clocks' intervals; each newly announced
 * one plans its clock's next tick that long after t. */
static int plan_clocks(const ssx_fmu_function *fn, void *instance, double t)
{
    fmi3_context *ctx = instance;
    size_t n = ctx->n_countdown_clocks;
    if (n == 0) {
        return fmi3OK;
    }
    if (fn[SLOT_GET_INTERVAL] == NULL) {
        fmi3_say(ctx, "the FMU has countdown clocks but does not provide fmi3GetIntervalDecimal");
        return fmi3Error;
    }
    int status = (int)FMI3(fn, SLOT_GET_INTERVAL, fmi3GetIntervalDecimalTYPE)(
        ctx->instance, ctx->countdown_clock_vr, n, ctx->countdown_answer,
        ctx->countdown_qualifier);
    if (status > fmi3Warning) {
        return status;
    }
    for (size_t i = 0; i < n; ++i) {
        if (ctx->countdown_qualifier[i] != fmi3IntervalChanged) {
            continue;
        }
        double interval = ctx->countdown_answer[i];
        if (!(interval > 0.0 && isfinite(interval))) {
            fmi3_say(ctx,
                "fmi3GetIntervalDecimal at t=%.17g announced the interval %.17g for the "
                "countdown clock %u: an interval is a positive number of seconds",
                t, interval, ctx->countdown_clock_vr[i]);
            return fmi3Error;
        }
        ctx->countdown_interval[i] = interval;
        ctx->countdown_next[i] = t + interval;
    }
    return status;
}

static int read_output_clocks(const ssx_fmu_function *fn, void *instance, int *active)
{
    fmi3_context *ctx = instance;
    if (ctx->n_output_clocks == 0) {
        return fmi3OK;
    }
    int status = (int)FMI3(fn, SLOT_GET_CLOCK, fmi3GetClockTYPE)(
        ctx->instance, ctx->output_clock_vr, ctx->n_output_clocks, ctx->output_clock_active);
    for (size_t k = 0; k < ctx->n_output_clocks; ++k) {
        active[k] = status <= fmi3Warning && ctx->output_clock_active[k] != fmi3False;
    }
    return status;
}

static int tick_triggered_clock(const ssx_fmu_function *fn, void *instance, size_t clock)
{
    fmi3_context *ctx = instance;
    fmi3Clock active = fmi3True;
    return (int)FMI3(fn, SLOT_SET_CLOCK, fmi3SetClockTYPE)(
        ctx->instance, &ctx->triggered_clock_vr[clock], 1, &active);
}

static size_t countdown_clocks(const void *context)
{
    return ((const fmi3_context *)context)->n_countdown_clocks;
}

static void clock_counts(const void *context, size_t *n_output, size_t *n_triggered)
{
    const fmi3_context *ctx = context;
    *n_output = ctx->n_output_clocks;
    *n_triggered = ctx->n_triggered_clocks;
}

static int do_step(const ssx_fmu_function *fn, void *instance, double t, double h,
                   int no_set_state_prior)
{
    fmi3_context *ctx = instance;
    /* a step that passes a clock's tick ends there: the engine ticks the clock and steps on */
    double full = h, tick = next_tick_after(ctx, t);
    int cut = tick < t + h && !ticks_near(ctx, tick, t + h);
    int at_tick = cut || ticks_near(ctx, tick, t + h);
    if (cut) {
        h = tick - t;
    }
    fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
    fmi3Float64 reached = t;
    if (ctx->n_intermediate > 0) {
        int started = start_moving(fn, ctx, t);
        if (started > fmi3Warning) {
            return started;
        }
    }
    int status = (int)FMI3(fn, SLOT_DO_STEP, fmi3DoStepTYPE)(
        ctx->instance, t, h, no_set_state_prior ? fmi3True : fmi3False, &event, &terminate, &early,
        &reached);
    ctx->moving = 0;
    ctx->outcome = (fmu_step_outcome){
        .reported = 1,
        .event_handling_needed = ctx->event_mode_used && event,
        .terminate_simulation = terminate != fmi3False,
        .early_return = ctx->early_return_allowed && early,
        .last_successful_time = reached,
        .events_at_step_end = ctx->event_mode_used && !ctx->early_return_allowed,
    };
    if (at_tick && !(ctx->outcome.early_return && reached < t + h)) {
        ctx->outcome.clock_tick = 1;
        ctx->outcome.early_return = cut;
        ctx->outcome.last_successful_time = cut ? tick : t + full;
    }
    return status;
}

static void step_outcome(void *instance, fmu_step_outcome *outcome)
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

/* Where the countdown plan saved with `state` lies among the saved ones; n_countdown_states
 * when none is. */
static size_t saved_plan(const fmi3_context *ctx, const void *state)
{
    size_t k = 0;
    while (k < ctx->n_countdown_states && ctx->countdown_states[k] != state) {
        ++k;
    }
    return k;
}

/* The countdown plan goes with the FMU state just taken: setting that state brings it back. */
static int save_plan(fmi3_context *ctx, void *state)
{
    size_t n = ctx->n_countdown_clocks, k = saved_plan(ctx, state);
    if (k == ctx->n_countdown_states) {
        void **states = realloc(ctx->countdown_states, (k + 1) * sizeof *states);
        if (states != NULL) {
            ctx->countdown_states = states;
        }
        double *plans = states != NULL
                        ? realloc(ctx->countdown_plans, (k + 1) * n * sizeof *plans) : NULL;
        if (plans == NULL) {
            fmi3_say(ctx, "out of memory keeping the countdown clocks' plan with an FMU state");
            return fmi3Error;
        }
        ctx->countdown_plans = plans;
        ctx->countdown_states[k] = state;
        ctx->n_countdown_states = k + 1;
    }
    memcpy(ctx->countdown_plans + k * n, ctx->countdown_next, n * sizeof *ctx->countdown_next);
    return fmi3OK;
}

static int get_state(const ssx_fmu_function *fn, void *instance, void **state)
{
    fmi3_context *ctx = instance;
    int status = (int)FMI3(fn, SLOT_GET_STATE, fmi3GetFMUStateTYPE)(ctx->instance, state);
    if (status > fmi3Warning || ctx->n_countdown_clocks == 0) {
        return status;
    }
    return worse_status(status, save_plan(ctx, *state));
}

static int set_state(const ssx_fmu_function *fn, void *instance, void *state)
{
    fmi3_context *ctx = instance;
    /* the restored instance has not stepped yet: no step's news apply to it */
    ctx->outcome = (fmu_step_outcome){0};
    int status = (int)FMI3(fn, SLOT_SET_STATE, fmi3SetFMUStateTYPE)(ctx->instance, state);
    size_t k = saved_plan(ctx, state), n = ctx->n_countdown_clocks;
    if (status <= fmi3Warning && k < ctx->n_countdown_states) {
        memcpy(ctx->countdown_next, ctx->countdown_plans + k * n,
               n * sizeof *ctx->countdown_next);
    }
    return status;
}

static int free_state(const ssx_fmu_function *fn, void *instance, void **state)
{
    fmi3_context *ctx = instance;
    size_t k = saved_plan(ctx, *state), n = ctx->n_countdown_clocks;
    if (k < ctx->n_countdown_states) {
        /* the last saved plan takes its place */
        size_t last = --ctx->n_countdown_states;
        ctx->countdown_states[k] = ctx->countdown_states[last];
        memmove(ctx->countdown_plans + k * n, ctx->countdown_plans + last * n,
                n * sizeof *ctx->countdown_plans);
    }
    return (int)FMI3(fn, SLOT_FREE_STATE, fmi3FreeFMUStateTYPE)(ctx->instance, state);
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

static int get_output_derivatives(const ssx_fmu_function *fn, void *instance,
                                  const unsigned int *vr, size_t n, const int *order,
                                  double *values)
{
    return (int)FMI3(fn, SLOT_GET_OUTPUT_DERIVATIVES, fmi3GetOutputDerivativesTYPE)(
        ((fmi3_context *)instance)->instance, vr, n, order, values, n);
}

/* ------------------------------------------------------------------ Model Exchange */

static void *instantiate_model_exchange(const ssx_fmu_function *fn, void *context, ssx_fmu_environment *environment,
                                        const char *instance_name, const char *token,
                                        const char *resource_path, int logging_on)
{
    fmi3_context *ctx = context;
    ctx->environment = environment;
    environment->handed = ctx;
    ctx->outcome = (fmu_step_outcome){0};
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

/* ------------------------------------------------------------------ Scheduled Execution */

/* Only the calls of its life cycle and partitions are required: the value calls are needed for
 * the types its ports have, and a hand-written binary may export no others. */
static const ssx_fmu_function_row fmi3_scheduled_functions[] = {
    {"fmi3InstantiateScheduledExecution", SLOT_INSTANTIATE, 1},
    {"fmi3FreeInstance", SLOT_FREE_INSTANCE, 1},
    {"fmi3EnterInitializationMode", SLOT_SETUP_EXPERIMENT, 1},
    {"fmi3EnterInitializationMode", SLOT_ENTER_INITIALIZATION_MODE, 1},
    {"fmi3ExitInitializationMode", SLOT_EXIT_INITIALIZATION_MODE, 1},
    {"fmi3Terminate", SLOT_TERMINATE, 1},
    {"fmi3ActivateModelPartition", SLOT_ACTIVATE_MODEL_PARTITION, 1},
    {"fmi3Reset", SLOT_RESET, 0},
    {"fmi3GetFloat64", SLOT_GET_REAL, 0},
    {"fmi3GetInt32", SLOT_GET_INTEGER, 0},
    {"fmi3GetBoolean", SLOT_GET_BOOLEAN, 0},
    {"fmi3SetFloat64", SLOT_SET_REAL, 0},
    {"fmi3SetInt32", SLOT_SET_INTEGER, 0},
    {"fmi3SetBoolean", SLOT_SET_BOOLEAN, 0},
    {"fmi3GetFloat32", SLOT_GET_FLOAT32, 0},
    {"fmi3GetInt8", SLOT_GET_INT8, 0},
    {"fmi3GetUInt8", SLOT_GET_UINT8, 0},
    {"fmi3GetInt16", SLOT_GET_INT16, 0},
    {"fmi3GetUInt16", SLOT_GET_UINT16, 0},
    {"fmi3GetUInt32", SLOT_GET_UINT32, 0},
    {"fmi3GetInt64", SLOT_GET_INT64, 0},
    {"fmi3GetUInt64", SLOT_GET_UINT64, 0},
    {"fmi3SetFloat32", SLOT_SET_FLOAT32, 0},
    {"fmi3SetInt8", SLOT_SET_INT8, 0},
    {"fmi3SetUInt8", SLOT_SET_UINT8, 0},
    {"fmi3SetInt16", SLOT_SET_INT16, 0},
    {"fmi3SetUInt16", SLOT_SET_UINT16, 0},
    {"fmi3SetUInt32", SLOT_SET_UINT32, 0},
    {"fmi3SetInt64", SLOT_SET_INT64, 0},
    {"fmi3SetUInt64", SLOT_SET_UINT64, 0},
    /* needed only when the FMU has output clocks, countdown or tunable clocks */
    {"fmi3GetClock", SLOT_GET_CLOCK, 0},
    {"fmi3GetIntervalDecimal", SLOT_GET_INTERVAL, 0},
};

/* The context of the partition running on this thread, NULL when `environment` is not the
 * one handed to the FMU being called or no partition runs. */
static fmi3_context *running_partition(const void *environment)
{
    fmi3_context *ctx = ssx_fmu_environment_claimed(environment) != NULL
                        ? (fmi3_context *)environment : NULL;
    return ctx != NULL && ctx->in_partition ? ctx : NULL;
}

/* The FMU's intermediate update inside a partition: an output clock ticked or a countdown
 * clock's interval became known. Both are read now, as the FMU may clear them when the
 * partition ends; a countdown clock ticks its interval after the partition's time. */
static void answer_clock_update(fmi3InstanceEnvironment environment)
{
    fmi3_context *ctx = running_partition(environment);
    if (ctx == NULL) {
        return;
    }
    const ssx_fmu_function *fn = ctx->fn;
    if (ctx->n_countdown_clocks > 0) {
        int status = fn[SLOT_GET_INTERVAL] == NULL ? fmi3Error
            : (int)FMI3(fn, SLOT_GET_INTERVAL, fmi3GetIntervalDecimalTYPE)(
                  ctx->instance, ctx->countdown_clock_vr, ctx->n_countdown_clocks,
                  ctx->countdown_answer, ctx->countdown_qualifier);
        ctx->update_status = worse_status(ctx->update_status, status);
        for (size_t i = 0; status <= fmi3Warning && i < ctx->n_countdown_clocks; ++i) {
            if (ctx->countdown_qualifier[i] == fmi3IntervalChanged) {
                ctx->countdown_next[i] = ctx->partition_time + ctx->countdown_answer[i];
            }
        }
    }
    if (ctx->n_output_clocks > 0) {
        int status = fn[SLOT_GET_CLOCK] == NULL ? fmi3Error
            : (int)FMI3(fn, SLOT_GET_CLOCK, fmi3GetClockTYPE)(
                  ctx->instance, ctx->output_clock_vr, ctx->n_output_clocks,
                  ctx->output_clock_active);
        ctx->update_status = worse_status(ctx->update_status, status);
        for (size_t k = 0; status <= fmi3Warning && k < ctx->n_output_clocks; ++k) {
            ctx->output_clock_ticked[k] = ctx->output_clock_ticked[k] || ctx->output_clock_active[k];
        }
    }
}

/* The preemption lock takes no environment: the partition running on this thread is the one
 * whose FMU locks. The engine runs one partition at a time, so there is nothing to hold off;
 * the lock only has to be balanced. */
static fmi3_context *locking_partition(void)
{
    ssx_fmu_environment *calling = ssx_fmu_environment_calling();
    return calling != NULL ? running_partition(calling->handed) : NULL;
}

static void lock_preemption(void)
{
    fmi3_context *ctx = locking_partition();
    if (ctx != NULL) {
        ++ctx->preemption_depth;
    }
}

static void unlock_preemption(void)
{
    fmi3_context *ctx = locking_partition();
    if (ctx != NULL) {
        --ctx->preemption_depth;
    }
}

static void *instantiate_scheduled(const ssx_fmu_function *fn, void *context,
                                   ssx_fmu_environment *environment, const char *instance_name,
                                   const char *token, const char *resource_path, int logging_on)
{
    fmi3_context *ctx = context;
    ctx->environment = environment;
    environment->handed = ctx;
    ctx->fn = fn;
    ctx->in_partition = 0;
    ctx->preemption_depth = 0;
    forget_countdown_plan(ctx);
    ctx->instance = FMI3(fn, SLOT_INSTANTIATE, fmi3InstantiateScheduledExecutionTYPE)(
        instance_name, token, resource_path, fmi3False, logging_on ? fmi3True : fmi3False, ctx,
        (fmi3LogMessageCallback)logger, answer_clock_update, lock_preemption, unlock_preemption);
    return ctx->instance != NULL ? ctx : NULL;
}

static int activate_model_partition(const ssx_fmu_function *fn, void *instance,
                                    unsigned int clock, double t)
{
    fmi3_context *ctx = instance;
    ctx->in_partition = 1;
    ctx->partition_time = t;
    ctx->update_status = fmi3OK;
    int status = (int)FMI3(fn, SLOT_ACTIVATE_MODEL_PARTITION, fmi3ActivateModelPartitionTYPE)(
        ctx->instance, clock, t);
    ctx->in_partition = 0;
    if (ctx->update_status > fmi3Warning) {
        fmi3_say(ctx, "the clockUpdate callback's fmi3GetClock or fmi3GetIntervalDecimal "
                      "failed in the partition of clock %u at t=%.17g", clock, t);
    }
    status = worse_status(status, ctx->update_status);
    if (ctx->preemption_depth != 0 && status <= fmi3Warning) {
        fmi3_say(ctx, ctx->preemption_depth < 0
                 ? "the FMU unlocked preemption it had not locked (partition of clock %u at "
                   "t=%.17g)"
                 : "the partition of clock %u returned with preemption locked (t=%.17g)",
                 clock, t);
        ctx->preemption_depth = 0;
        status = fmi3Error;
    }
    return status;
}

static int get_interval(const ssx_fmu_function *fn, void *instance, unsigned int clock,
                        double *interval, int *qualifier)
{
    fmi3_context *ctx = instance;
    fmi3Float64 value = 0.0;
    fmi3IntervalQualifier answer = fmi3IntervalNotYetKnown;
    int status = (int)FMI3(fn, SLOT_GET_INTERVAL, fmi3GetIntervalDecimalTYPE)(
        ctx->instance, &clock, 1, &value, &answer);
    *interval = value;
    *qualifier = (int)answer;
    return status;
}

static void take_clock_updates(void *context, int *ticked, double *next)
{
    fmi3_context *ctx = context;
    for (size_t k = 0; k < ctx->n_output_clocks; ++k) {
        ticked[k] = ctx->output_clock_ticked[k] != fmi3False;
        ctx->output_clock_ticked[k] = fmi3False;
    }
    for (size_t i = 0; i < ctx->n_countdown_clocks; ++i) {
        next[i] = ctx->countdown_next[i];
        ctx->countdown_next[i] = INFINITY;
    }
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
    .directional_derivative = directional_derivative,                                         \
    .get_output_derivatives = get_output_derivatives,                                         \
    .set_input_derivatives = set_input_derivatives, .get_string = get_string,               \
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
    .tick_clocks = tick_clocks,
    .next_clock_tick = next_clock_tick,
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
    .tick_clocks = tick_clocks,
    .read_output_clocks = read_output_clocks,
    .plan_clocks = plan_clocks,
    .countdown_clocks = countdown_clocks,
    .tick_triggered_clock = tick_triggered_clock,
    .clock_counts = clock_counts,
    .step_outcome = step_outcome,
};

const ssx_fmu_backend ssx_fmi3_scheduled_backend = {
    FMI3_ADAPTERS,
    .standard = "FMI 3.0 Scheduled Execution",
    .interface = SSX_SCHEDULED_EXECUTION,
    .functions = fmi3_scheduled_functions,
    .n_functions = sizeof fmi3_scheduled_functions / sizeof fmi3_scheduled_functions[0],
    .instantiate = instantiate_scheduled,
    .exit_initialization_mode = exit_initialization_mode_model_exchange,
    .activate_model_partition = activate_model_partition,
    .take_clock_updates = take_clock_updates,
    .get_interval = get_interval,
    .clock_counts = clock_counts,
    .countdown_clocks = countdown_clocks,
};
