/* The FMI 1.0 back-ends of the FMU binding, Co-Simulation and Model Exchange: the fmi
 * functions (exported as <modelIdentifier>_fmiXxx, which the binding resolves), which of them
 * a binary must export for each interface, and adapters that call each with its FMI 1.0 type.
 *
 * FMI 1.0 has fewer steps than the binding's life cycle: no setup experiment, no
 * initialization mode (start values are set before fmiInitializeSlave / fmiInitialize), no
 * event mode to enter or leave (fmiEventUpdate is the event iteration). The instance the
 * binding holds is this back-end's context, which keeps the experiment for the one
 * initializing call and, for Model Exchange, what fmiInitialize said about the first event
 * iteration. FMI 1.0 has no FMU state: its slots stay empty, so rollback is refused. */
#include "fmu_backend.h"

#include <stdlib.h>

#include "fmi1Functions.h"
#include "fmu_message.h"

/* FMI 1.0 Model Exchange passes three callbacks by value (the Co-Simulation struct of
 * fmi1Functions.h adds stepFinished): the standard's struct and the instantiate function that
 * takes it. */
typedef struct {
    fmi1CallbackLogger logger;
    fmi1CallbackAllocateMemory allocateMemory;
    fmi1CallbackFreeMemory freeMemory;
} fmi1_model_callbacks;
typedef fmi1Component fmi1_instantiate_model(fmi1String instance_name, fmi1String guid,
                                             fmi1_model_callbacks functions,
                                             fmi1Boolean logging_on);

typedef struct {
    fmi1Component component;
    double start_time;
    int stop_time_defined;
    double stop_time;
    int tolerance_defined;
    double tolerance;
    /* Model Exchange: what fmiInitialize said, answered to the first event iteration */
    fmi1EventInfo initialized;
    int initialized_unread;
} fmi1_context;

/* FMI 1.0's logger names the FMU's own component, which is NULL while it is instantiated,
 * not an environment of ours: the FMU that logs is the one whose call is in progress on this
 * thread, which the binding marks (ssx_fmu_environment_enter). */
static void logger(fmi1Component component, fmi1String instance_name, fmi1Status status,
                   fmi1String category, fmi1String message, ...)
{
    (void)component;
    (void)instance_name;
    (void)status;
    (void)category;
    if (message == NULL) {
        return;
    }
    char text[SSX_FMU_MESSAGE_SIZE];
    va_list args;
    va_start(args, message);
    ssx_format_fmu_message(text, sizeof text, message, args);
    va_end(args);
    ssx_fmu_environment_log(ssx_fmu_environment_calling(), text);
}

/* The function in `slot` with its FMI 1.0 type (ISO C converts between function pointers). */
#define FMI1(fn, slot, type) ((type *)(fn)[slot])
/* A call on the context's component, as an int status (the binding marks the call for the
 * logger). */
#define CALL(ctx, expression) return (void)(ctx), (int)(expression)
#define COMPONENT(instance) (((fmi1_context *)(instance))->component)

/* ------------------------------------------------------------------ life cycle */

static void *instantiated(fmi1_context *ctx, fmi1Component component)
{
    ctx->component = component;
    return component != NULL ? ctx : NULL;
}

static void *instantiate_slave(const ssx_fmu_function *fn, void *context, ssx_fmu_environment *environment,
                               const char *instance_name, const char *guid,
                               const char *fmu_location, int logging_on)
{
    fmi1_context *ctx = context;
    (void)environment; /* FMI 1.0 hands the FMU none */
    *ctx = (fmi1_context){0};
    fmi1CallbackFunctions callbacks = {logger, calloc, free, NULL};
    fmi1Component component = FMI1(fn, SLOT_INSTANTIATE, fmi1InstantiateSlaveTYPE)(
        instance_name, guid, fmu_location, "application/x-fmu-sharedlibrary", 0.0, fmi1False,
        fmi1False, callbacks, logging_on ? fmi1True : fmi1False);
    return instantiated(ctx, component);
}

static void *instantiate_model(const ssx_fmu_function *fn, void *context, ssx_fmu_environment *environment,
                               const char *instance_name, const char *guid,
                               const char *resource_uri, int logging_on)
{
    (void)resource_uri; /* FMI 1.0 Model Exchange has no resources */
    fmi1_context *ctx = context;
    (void)environment; /* FMI 1.0 hands the FMU none */
    *ctx = (fmi1_context){0};
    fmi1_model_callbacks callbacks = {logger, calloc, free};
    fmi1Component component = FMI1(fn, SLOT_INSTANTIATE, fmi1_instantiate_model)(
        instance_name, guid, callbacks, logging_on ? fmi1True : fmi1False);
    return instantiated(ctx, component);
}

static void free_slave(const ssx_fmu_function *fn, void *instance)
{
    FMI1(fn, SLOT_FREE_INSTANCE, fmi1FreeSlaveInstanceTYPE)(COMPONENT(instance));
}

static void free_model(const ssx_fmu_function *fn, void *instance)
{
    FMI1(fn, SLOT_FREE_INSTANCE, fmi1FreeModelInstanceTYPE)(COMPONENT(instance));
}

/* Kept for the initializing call; Model Exchange sets its start time now. */
static int keep_experiment(void *instance, int tolerance_defined, double tolerance,
                           double start_time, int stop_time_defined, double stop_time)
{
    fmi1_context *ctx = instance;
    ctx->tolerance_defined = tolerance_defined;
    ctx->tolerance = tolerance;
    ctx->start_time = start_time;
    ctx->stop_time_defined = stop_time_defined;
    ctx->stop_time = stop_time;
    return 0;
}

static int setup_slave(const ssx_fmu_function *fn, void *instance, int tolerance_defined,
                       double tolerance, double start_time, int stop_time_defined,
                       double stop_time)
{
    (void)fn;
    return keep_experiment(instance, tolerance_defined, tolerance, start_time, stop_time_defined,
                           stop_time);
}

static int setup_model(const ssx_fmu_function *fn, void *instance, int tolerance_defined,
                       double tolerance, double start_time, int stop_time_defined,
                       double stop_time)
{
    (void)keep_experiment(instance, tolerance_defined, tolerance, start_time, stop_time_defined,
                          stop_time);
    CALL(instance, FMI1(fn, SLOT_SETUP_EXPERIMENT, fmi1SetTimeTYPE)(COMPONENT(instance),
                                                                    start_time));
}

/* FMI 1.0 has no initialization mode: start values are set on the instantiated FMU. */
static int no_call(const ssx_fmu_function *fn, void *instance)
{
    (void)fn;
    (void)instance;
    return 0;
}

static int initialize_slave(const ssx_fmu_function *fn, void *instance)
{
    fmi1_context *ctx = instance;
    CALL(ctx, FMI1(fn, SLOT_EXIT_INITIALIZATION_MODE, fmi1InitializeSlaveTYPE)(
                  ctx->component, ctx->start_time,
                  ctx->stop_time_defined ? fmi1True : fmi1False, ctx->stop_time));
}

static int initialize_model(const ssx_fmu_function *fn, void *instance)
{
    fmi1_context *ctx = instance;
    ctx->initialized = (fmi1EventInfo){0};
    ctx->initialized_unread = 1;
    CALL(ctx, FMI1(fn, SLOT_EXIT_INITIALIZATION_MODE, fmi1InitializeTYPE)(
                  ctx->component, ctx->tolerance_defined ? fmi1True : fmi1False,
                  ctx->tolerance, &ctx->initialized));
}

static int terminate_slave(const ssx_fmu_function *fn, void *instance)
{
    CALL(instance, FMI1(fn, SLOT_TERMINATE, fmi1TerminateSlaveTYPE)(COMPONENT(instance)));
}

static int terminate_model(const ssx_fmu_function *fn, void *instance)
{
    CALL(instance, FMI1(fn, SLOT_TERMINATE, fmi1TerminateTYPE)(COMPONENT(instance)));
}

static int reset_slave(const ssx_fmu_function *fn, void *instance)
{
    CALL(instance, FMI1(fn, SLOT_RESET, fmi1ResetSlaveTYPE)(COMPONENT(instance)));
}

/* ------------------------------------------------------------------ values */

static int get_real(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    double *values)
{
    CALL(instance, FMI1(fn, SLOT_GET_REAL, fmi1GetRealTYPE)(COMPONENT(instance), vr, n, values));
}

static int get_integer(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, int *values)
{
    CALL(instance,
         FMI1(fn, SLOT_GET_INTEGER, fmi1GetIntegerTYPE)(COMPONENT(instance), vr, n, values));
}

static int set_real(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    const double *values)
{
    CALL(instance, FMI1(fn, SLOT_SET_REAL, fmi1SetRealTYPE)(COMPONENT(instance), vr, n, values));
}

static int set_integer(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, const int *values)
{
    CALL(instance,
         FMI1(fn, SLOT_SET_INTEGER, fmi1SetIntegerTYPE)(COMPONENT(instance), vr, n, values));
}

/* The texts fmiGetString returns are the FMU's until its next call: the caller copies them. */
static int get_string(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                      size_t n, const char **values)
{
    CALL(instance,
         FMI1(fn, SLOT_GET_STRING, fmi1GetStringTYPE)(COMPONENT(instance), vr, n, values));
}

static int set_string(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                      size_t n, const char *const *values)
{
    CALL(instance,
         FMI1(fn, SLOT_SET_STRING, fmi1SetStringTYPE)(COMPONENT(instance), vr, n, values));
}

/* fmiBoolean is a char: the engine's ints cross in chunks through a buffer on the stack. */
enum { BOOLEAN_CHUNK = 64 };

static int get_boolean(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, int *values)
{
    int worst = 0;
    for (size_t first = 0; first < n && worst <= 1; first += BOOLEAN_CHUNK) {
        fmi1Boolean chunk[BOOLEAN_CHUNK];
        size_t count = n - first < BOOLEAN_CHUNK ? n - first : BOOLEAN_CHUNK;
        int status = (int)FMI1(fn, SLOT_GET_BOOLEAN, fmi1GetBooleanTYPE)(
            COMPONENT(instance), vr + first, count, chunk);
        for (size_t i = 0; i < count; ++i) {
            values[first + i] = chunk[i] != fmi1False;
        }
        worst = status > worst ? status : worst;
    }
    return worst;
}

static int set_boolean(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, const int *values)
{
    int worst = 0;
    for (size_t first = 0; first < n && worst <= 1; first += BOOLEAN_CHUNK) {
        fmi1Boolean chunk[BOOLEAN_CHUNK];
        size_t count = n - first < BOOLEAN_CHUNK ? n - first : BOOLEAN_CHUNK;
        for (size_t i = 0; i < count; ++i) {
            chunk[i] = values[first + i] ? fmi1True : fmi1False;
        }
        int status = (int)FMI1(fn, SLOT_SET_BOOLEAN, fmi1SetBooleanTYPE)(
            COMPONENT(instance), vr + first, count, chunk);
        worst = status > worst ? status : worst;
    }
    return worst;
}

/* ------------------------------------------------------------------ Co-Simulation */

/* newStep: the previous step was accepted, always (an FMI 1.0 FMU is never rolled back). */
static int do_step(const ssx_fmu_function *fn, void *instance, double t, double h,
                   int no_set_state_prior)
{
    (void)no_set_state_prior;
    CALL(instance,
         FMI1(fn, SLOT_DO_STEP, fmi1DoStepTYPE)(COMPONENT(instance), t, h, fmi1True));
}

static int get_last_successful_time(const ssx_fmu_function *fn, void *instance, double *time)
{
    CALL(instance, FMI1(fn, SLOT_GET_LAST_SUCCESSFUL_TIME, fmi1GetRealStatusTYPE)(
                       COMPONENT(instance), fmi1LastSuccessfulTime, time));
}

/* ------------------------------------------------------------------ Model Exchange */

static int set_time(const ssx_fmu_function *fn, void *instance, double time)
{
    CALL(instance, FMI1(fn, SLOT_SET_TIME, fmi1SetTimeTYPE)(COMPONENT(instance), time));
}

static int set_continuous_states(const ssx_fmu_function *fn, void *instance, const double *x,
                                 size_t nx)
{
    CALL(instance, FMI1(fn, SLOT_SET_CONTINUOUS_STATES, fmi1SetContinuousStatesTYPE)(
                       COMPONENT(instance), x, nx));
}

static int get_continuous_states(const ssx_fmu_function *fn, void *instance, double *x,
                                 size_t nx)
{
    CALL(instance, FMI1(fn, SLOT_GET_CONTINUOUS_STATES, fmi1GetContinuousStatesTYPE)(
                       COMPONENT(instance), x, nx));
}

static int get_derivatives(const ssx_fmu_function *fn, void *instance, double *dx, size_t nx)
{
    CALL(instance, FMI1(fn, SLOT_GET_DERIVATIVES, fmi1GetDerivativesTYPE)(COMPONENT(instance),
                                                                          dx, nx));
}

static int get_event_indicators(const ssx_fmu_function *fn, void *instance, double *z,
                                size_t nz)
{
    CALL(instance, FMI1(fn, SLOT_GET_EVENT_INDICATORS, fmi1GetEventIndicatorsTYPE)(
                       COMPONENT(instance), z, nz));
}

static int get_nominals_of_continuous_states(const ssx_fmu_function *fn, void *instance,
                                             double *nominals, size_t nx)
{
    CALL(instance, FMI1(fn, SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES,
                        fmi1GetNominalContinuousStatesTYPE)(COMPONENT(instance), nominals, nx));
}

static void tell(const fmi1EventInfo *event, ssx_fmu_event_info *info)
{
    *info = (ssx_fmu_event_info){
        .new_discrete_states_needed = event->iterationConverged == fmi1False,
        .terminate_simulation = event->terminateSimulation != fmi1False,
        .nominals_changed = event->stateValueReferencesChanged != fmi1False,
        .values_changed = event->stateValuesChanged != fmi1False,
        .next_event_time_defined = event->upcomingTimeEvent != fmi1False,
        .next_event_time = event->nextEventTime,
    };
}

/* The event iteration: fmiEventUpdate without intermediate results (the FMU iterates until it
 * converged); the first after fmiInitialize is what fmiInitialize said, when it converged. */
static int event_update(const ssx_fmu_function *fn, void *instance, ssx_fmu_event_info *info)
{
    fmi1_context *ctx = instance;
    if (ctx->initialized_unread) {
        ctx->initialized_unread = 0;
        if (ctx->initialized.iterationConverged != fmi1False) {
            tell(&ctx->initialized, info);
            return 0;
        }
    }
    fmi1EventInfo event = {0};
    int status = (int)FMI1(fn, SLOT_NEW_DISCRETE_STATES, fmi1EventUpdateTYPE)(
        ctx->component, fmi1False, &event);
    tell(&event, info);
    return status;
}

static int completed_integrator_step(const ssx_fmu_function *fn, void *instance,
                                     int no_set_state_prior, int *enter_event_mode,
                                     int *terminate_simulation)
{
    (void)no_set_state_prior;
    fmi1Boolean call_event_update = fmi1False;
    int status = (int)FMI1(fn, SLOT_COMPLETED_INTEGRATOR_STEP, fmi1CompletedIntegratorStepTYPE)(
        COMPONENT(instance), &call_event_update);
    *enter_event_mode = call_event_update != fmi1False;
    *terminate_simulation = 0;
    return status;
}

/* ------------------------------------------------------------------ the tables */

/* A slot FMI 1.0 has no function for is filled with the function it is part of (the
 * experiment and the initialization mode are fmiInitializeSlave's arguments and timing), so
 * that the binding calls its adapter and names that function. */
#define FMI1_VALUE_ROWS                                                                       \
    {"fmiGetReal", SLOT_GET_REAL, 1},                                                         \
    {"fmiGetInteger", SLOT_GET_INTEGER, 1},                                                   \
    {"fmiGetBoolean", SLOT_GET_BOOLEAN, 1},                                                   \
    {"fmiSetReal", SLOT_SET_REAL, 1},                                                         \
    {"fmiSetInteger", SLOT_SET_INTEGER, 1},                                                   \
    {"fmiSetBoolean", SLOT_SET_BOOLEAN, 1},                                                   \
    {"fmiGetString", SLOT_GET_STRING, 0},                                                     \
    {"fmiSetString", SLOT_SET_STRING, 0},

static const ssx_fmu_function_row fmi1_functions[] = {
    {"fmiInstantiateSlave", SLOT_INSTANTIATE, 1},
    {"fmiFreeSlaveInstance", SLOT_FREE_INSTANCE, 1},
    {"fmiInitializeSlave", SLOT_SETUP_EXPERIMENT, 1},
    {"fmiInitializeSlave", SLOT_ENTER_INITIALIZATION_MODE, 1},
    {"fmiInitializeSlave", SLOT_EXIT_INITIALIZATION_MODE, 1},
    {"fmiTerminateSlave", SLOT_TERMINATE, 1},
    {"fmiDoStep", SLOT_DO_STEP, 1},
    FMI1_VALUE_ROWS
    /* capabilities an FMU may lack */
    {"fmiResetSlave", SLOT_RESET, 0},
    {"fmiGetRealStatus", SLOT_GET_LAST_SUCCESSFUL_TIME, 0},
};

static const ssx_fmu_function_row fmi1_model_exchange_functions[] = {
    {"fmiInstantiateModel", SLOT_INSTANTIATE, 1},
    {"fmiFreeModelInstance", SLOT_FREE_INSTANCE, 1},
    {"fmiSetTime", SLOT_SETUP_EXPERIMENT, 1},
    {"fmiInitialize", SLOT_ENTER_INITIALIZATION_MODE, 1},
    {"fmiInitialize", SLOT_EXIT_INITIALIZATION_MODE, 1},
    {"fmiTerminate", SLOT_TERMINATE, 1},
    FMI1_VALUE_ROWS
    {"fmiSetTime", SLOT_SET_TIME, 1},
    {"fmiSetContinuousStates", SLOT_SET_CONTINUOUS_STATES, 1},
    {"fmiGetContinuousStates", SLOT_GET_CONTINUOUS_STATES, 1},
    {"fmiGetDerivatives", SLOT_GET_DERIVATIVES, 1},
    {"fmiGetEventIndicators", SLOT_GET_EVENT_INDICATORS, 1},
    {"fmiGetNominalContinuousStates", SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES, 1},
    {"fmiEventUpdate", SLOT_ENTER_EVENT_MODE, 1},
    {"fmiEventUpdate", SLOT_NEW_DISCRETE_STATES, 1},
    {"fmiEventUpdate", SLOT_ENTER_CONTINUOUS_TIME_MODE, 1},
    {"fmiCompletedIntegratorStep", SLOT_COMPLETED_INTEGRATOR_STEP, 1},
};

#define FMI1_NAME(name) "fmi" #name,
static const char *const fmi1_status_names[] = {SSX_STATUS_NAMES(FMI1_NAME)};

#define FMI1_ADAPTERS                                                                         \
    .version = "FMI 1.0", .status_names = fmi1_status_names,                                  \
    .context_size = sizeof(fmi1_context), .enter_initialization_mode = no_call,               \
    .get_real = get_real, .get_integer = get_integer, .get_boolean = get_boolean,             \
    .set_real = set_real, .set_integer = set_integer, .set_boolean = set_boolean,             \
    .get_string = get_string, .set_string = set_string

const ssx_fmu_backend ssx_fmi1_backend = {
    FMI1_ADAPTERS,
    .standard = "FMI 1.0 Co-Simulation",
    .interface = SSX_CO_SIMULATION,
    .functions = fmi1_functions,
    .n_functions = sizeof fmi1_functions / sizeof fmi1_functions[0],
    .instantiate = instantiate_slave,
    .free_instance = free_slave,
    .setup_experiment = setup_slave,
    .exit_initialization_mode = initialize_slave,
    .terminate = terminate_slave,
    .reset = reset_slave,
    .do_step = do_step,
    .get_last_successful_time = get_last_successful_time,
};

const ssx_fmu_backend ssx_fmi1_model_exchange_backend = {
    FMI1_ADAPTERS,
    .standard = "FMI 1.0 Model Exchange",
    .interface = SSX_MODEL_EXCHANGE,
    .functions = fmi1_model_exchange_functions,
    .n_functions = sizeof fmi1_model_exchange_functions / sizeof fmi1_model_exchange_functions[0],
    .instantiate = instantiate_model,
    .free_instance = free_model,
    .setup_experiment = setup_model,
    .exit_initialization_mode = initialize_model,
    .terminate = terminate_model,
    .set_time = set_time,
    .set_continuous_states = set_continuous_states,
    .get_continuous_states = get_continuous_states,
    .get_derivatives = get_derivatives,
    .get_event_indicators = get_event_indicators,
    .get_nominals_of_continuous_states = get_nominals_of_continuous_states,
    .enter_event_mode = no_call,
    .new_discrete_states = event_update,
    .enter_continuous_time_mode = no_call,
    .completed_integrator_step = completed_integrator_step,
};
