/* The FMI 2.0 back-ends of the FMU binding, Co-Simulation and Model Exchange: the fmi2
 * functions, which of them a binary must export for each interface, and adapters that call each
 * with its fmi2 type. */
#include "fmu_backend.h"

#include <stdlib.h>

#include "fmi2Functions.h"
#include "fmu_binding.h"
#include "fmu_message.h"

/* The rows both interfaces share: required, then optional. */
#define FMI2_COMMON_ROWS                                                                      \
    {"fmi2Instantiate", SLOT_INSTANTIATE, 1},                                                 \
    {"fmi2FreeInstance", SLOT_FREE_INSTANCE, 1},                                              \
    {"fmi2SetupExperiment", SLOT_SETUP_EXPERIMENT, 1},                                        \
    {"fmi2EnterInitializationMode", SLOT_ENTER_INITIALIZATION_MODE, 1},                       \
    {"fmi2ExitInitializationMode", SLOT_EXIT_INITIALIZATION_MODE, 1},                         \
    {"fmi2Terminate", SLOT_TERMINATE, 1},                                                     \
    {"fmi2Reset", SLOT_RESET, 1},                                                             \
    {"fmi2GetReal", SLOT_GET_REAL, 1},                                                        \
    {"fmi2GetInteger", SLOT_GET_INTEGER, 1},                                                  \
    {"fmi2GetBoolean", SLOT_GET_BOOLEAN, 1},                                                  \
    {"fmi2SetReal", SLOT_SET_REAL, 1},                                                        \
    {"fmi2SetInteger", SLOT_SET_INTEGER, 1},                                                  \
    {"fmi2SetBoolean", SLOT_SET_BOOLEAN, 1},
#define FMI2_OPTIONAL_ROWS                                                                    \
    {"fmi2GetString", SLOT_GET_STRING, 0},                                                    \
    {"fmi2SetString", SLOT_SET_STRING, 0},                                                    \
    {"fmi2GetFMUstate", SLOT_GET_STATE, 0},                                                   \
    {"fmi2SetFMUstate", SLOT_SET_STATE, 0},                                                   \
    {"fmi2FreeFMUstate", SLOT_FREE_STATE, 0},                                                 \
    {"fmi2SerializedFMUstateSize", SLOT_SERIALIZED_STATE_SIZE, 0},                            \
    {"fmi2SerializeFMUstate", SLOT_SERIALIZE_STATE, 0},                                       \
    {"fmi2DeSerializeFMUstate", SLOT_DESERIALIZE_STATE, 0},                                   \
    {"fmi2GetDirectionalDerivative", SLOT_DIRECTIONAL_DERIVATIVE, 0},                         \
    {"fmi2SetRealInputDerivatives", SLOT_SET_INPUT_DERIVATIVES, 0},                           \
    {"fmi2GetRealOutputDerivatives", SLOT_GET_OUTPUT_DERIVATIVES, 0},

static const ssx_fmu_function_row fmi2_functions[] = {
    FMI2_COMMON_ROWS
    {"fmi2DoStep", SLOT_DO_STEP, 1},
    /* capabilities an FMU may lack */
    FMI2_OPTIONAL_ROWS
    {"fmi2GetBooleanStatus", SLOT_GET_TERMINATED, 0},
    {"fmi2GetRealStatus", SLOT_GET_LAST_SUCCESSFUL_TIME, 0},
};

/* Model Exchange: the common functions, the ones of the interface instead of fmi2DoStep. */
static const ssx_fmu_function_row fmi2_model_exchange_functions[] = {
    FMI2_COMMON_ROWS
    {"fmi2SetTime", SLOT_SET_TIME, 1},
    {"fmi2SetContinuousStates", SLOT_SET_CONTINUOUS_STATES, 1},
    {"fmi2GetContinuousStates", SLOT_GET_CONTINUOUS_STATES, 1},
    {"fmi2GetDerivatives", SLOT_GET_DERIVATIVES, 1},
    {"fmi2GetEventIndicators", SLOT_GET_EVENT_INDICATORS, 1},
    {"fmi2GetNominalsOfContinuousStates", SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES, 1},
    {"fmi2EnterEventMode", SLOT_ENTER_EVENT_MODE, 1},
    {"fmi2NewDiscreteStates", SLOT_NEW_DISCRETE_STATES, 1},
    {"fmi2EnterContinuousTimeMode", SLOT_ENTER_CONTINUOUS_TIME_MODE, 1},
    {"fmi2CompletedIntegratorStep", SLOT_COMPLETED_INTEGRATOR_STEP, 1},
    FMI2_OPTIONAL_ROWS
};

#define FMI2_NAME(name) "fmi2" #name,
static const char *const fmi2_status_names[] = {SSX_STATUS_NAMES(FMI2_NAME)};

const char *ssx_fmi2_status_name(int status)
{
    if (status >= 0 && status < (int)(sizeof fmi2_status_names / sizeof fmi2_status_names[0])) {
        return fmi2_status_names[status];
    }
    return "no fmi2 status (the engine failed)";
}

/* The function in `slot` with its fmi2 type (ISO C converts between function pointer types). */
#define FMI2(fn, slot, type) ((type *)(fn)[slot])

static void logger(fmi2ComponentEnvironment environment, fmi2String instance_name,
                   fmi2Status status, fmi2String category, fmi2String message, ...)
{
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
    /* some FMUs name no environment, or another: the pointer is checked, never read */
    ssx_fmu_environment_log(ssx_fmu_environment_claimed(environment), text);
}

/* The callbacks live in the context: FMI 2.0 lets the instance keep the pointer. */
static void *instantiate_as(fmi2Type type, const ssx_fmu_function *fn, void *context,
                            ssx_fmu_environment *environment, const char *instance_name, const char *guid,
                            const char *resource_uri, int logging_on)
{
    fmi2CallbackFunctions *callbacks = context;
    *callbacks = (fmi2CallbackFunctions){logger, calloc, free, NULL, environment};
    environment->handed = environment;
    return FMI2(fn, SLOT_INSTANTIATE, fmi2InstantiateTYPE)(
        instance_name, type, guid, resource_uri, callbacks, fmi2False,
        logging_on ? fmi2True : fmi2False);
}

static void *instantiate(const ssx_fmu_function *fn, void *context, ssx_fmu_environment *environment,
                         const char *instance_name, const char *guid, const char *resource_uri,
                         int logging_on)
{
    return instantiate_as(fmi2CoSimulation, fn, context, environment, instance_name, guid, resource_uri,
                          logging_on);
}

static void *instantiate_model_exchange(const ssx_fmu_function *fn, void *context, ssx_fmu_environment *environment,
                                        const char *instance_name, const char *guid,
                                        const char *resource_uri, int logging_on)
{
    return instantiate_as(fmi2ModelExchange, fn, context, environment, instance_name, guid,
                          resource_uri, logging_on);
}

static void free_instance(const ssx_fmu_function *fn, void *instance)
{
    FMI2(fn, SLOT_FREE_INSTANCE, fmi2FreeInstanceTYPE)(instance);
}

static int setup_experiment(const ssx_fmu_function *fn, void *instance, int tolerance_defined,
                            double tolerance, double start_time, int stop_time_defined,
                            double stop_time)
{
    return (int)FMI2(fn, SLOT_SETUP_EXPERIMENT, fmi2SetupExperimentTYPE)(
        instance, tolerance_defined ? fmi2True : fmi2False, tolerance, start_time,
        stop_time_defined ? fmi2True : fmi2False, stop_time);
}

static int enter_initialization_mode(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI2(fn, SLOT_ENTER_INITIALIZATION_MODE,
                     fmi2EnterInitializationModeTYPE)(instance);
}

static int exit_initialization_mode(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI2(fn, SLOT_EXIT_INITIALIZATION_MODE, fmi2ExitInitializationModeTYPE)(instance);
}

static int terminate(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI2(fn, SLOT_TERMINATE, fmi2TerminateTYPE)(instance);
}

static int reset(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI2(fn, SLOT_RESET, fmi2ResetTYPE)(instance);
}

static int get_real(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    double *values)
{
    return (int)FMI2(fn, SLOT_GET_REAL, fmi2GetRealTYPE)(instance, vr, n, values);
}

static int get_integer(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, int *values)
{
    return (int)FMI2(fn, SLOT_GET_INTEGER, fmi2GetIntegerTYPE)(instance, vr, n, values);
}

static int get_boolean(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, int *values)
{
    return (int)FMI2(fn, SLOT_GET_BOOLEAN, fmi2GetBooleanTYPE)(instance, vr, n, values);
}

static int set_real(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    const double *values)
{
    return (int)FMI2(fn, SLOT_SET_REAL, fmi2SetRealTYPE)(instance, vr, n, values);
}

static int set_integer(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, const int *values)
{
    return (int)FMI2(fn, SLOT_SET_INTEGER, fmi2SetIntegerTYPE)(instance, vr, n, values);
}

static int set_boolean(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, const int *values)
{
    return (int)FMI2(fn, SLOT_SET_BOOLEAN, fmi2SetBooleanTYPE)(instance, vr, n, values);
}

/* The texts fmi2GetString returns are the FMU's until its next call: the caller copies them. */
static int get_string(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                      size_t n, const char **values)
{
    return (int)FMI2(fn, SLOT_GET_STRING, fmi2GetStringTYPE)(instance, vr, n, values);
}

static int set_string(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                      size_t n, const char *const *values)
{
    return (int)FMI2(fn, SLOT_SET_STRING, fmi2SetStringTYPE)(instance, vr, n, values);
}

static int do_step(const ssx_fmu_function *fn, void *instance, double t, double h,
                   int no_set_state_prior)
{
    return (int)FMI2(fn, SLOT_DO_STEP, fmi2DoStepTYPE)(instance, t, h,
                                                       no_set_state_prior ? fmi2True : fmi2False);
}

static int get_state(const ssx_fmu_function *fn, void *instance, void **state)
{
    return (int)FMI2(fn, SLOT_GET_STATE, fmi2GetFMUstateTYPE)(instance, state);
}

static int set_state(const ssx_fmu_function *fn, void *instance, void *state)
{
    return (int)FMI2(fn, SLOT_SET_STATE, fmi2SetFMUstateTYPE)(instance, state);
}

static int free_state(const ssx_fmu_function *fn, void *instance, void **state)
{
    return (int)FMI2(fn, SLOT_FREE_STATE, fmi2FreeFMUstateTYPE)(instance, state);
}

static int serialized_state_size(const ssx_fmu_function *fn, void *instance, void *state,
                                 size_t *size)
{
    return (int)FMI2(fn, SLOT_SERIALIZED_STATE_SIZE, fmi2SerializedFMUstateSizeTYPE)(
        instance, state, size);
}

static int serialize_state(const ssx_fmu_function *fn, void *instance, void *state, char *bytes,
                           size_t size)
{
    return (int)FMI2(fn, SLOT_SERIALIZE_STATE, fmi2SerializeFMUstateTYPE)(instance, state, bytes,
                                                                         size);
}

static int deserialize_state(const ssx_fmu_function *fn, void *instance, const char *bytes,
                             size_t size, void **state)
{
    return (int)FMI2(fn, SLOT_DESERIALIZE_STATE, fmi2DeSerializeFMUstateTYPE)(instance, bytes,
                                                                             size, state);
}

static int directional_derivative(const ssx_fmu_function *fn, void *instance,
                                  const unsigned int *unknowns, size_t n_unknowns,
                                  const unsigned int *knowns, size_t n_knowns,
                                  const double *dv_known, double *dv_unknown)
{
    return (int)FMI2(fn, SLOT_DIRECTIONAL_DERIVATIVE, fmi2GetDirectionalDerivativeTYPE)(
        instance, unknowns, n_unknowns, knowns, n_knowns, dv_known, dv_unknown);
}

static int set_input_derivatives(const ssx_fmu_function *fn, void *instance,
                                 const unsigned int *vr, size_t n, const int *order,
                                 const double *values)
{
    return (int)FMI2(fn, SLOT_SET_INPUT_DERIVATIVES, fmi2SetRealInputDerivativesTYPE)(
        instance, vr, n, order, values);
}

static int get_output_derivatives(const ssx_fmu_function *fn, void *instance,
                                  const unsigned int *vr, size_t n, const int *order,
                                  double *values)
{
    return (int)FMI2(fn, SLOT_GET_OUTPUT_DERIVATIVES, fmi2GetRealOutputDerivativesTYPE)(
        instance, vr, n, order, values);
}

static int get_terminated(const ssx_fmu_function *fn, void *instance, int *terminated)
{
    fmi2Boolean value = fmi2False;
    int status = (int)FMI2(fn, SLOT_GET_TERMINATED, fmi2GetBooleanStatusTYPE)(
        instance, fmi2Terminated, &value);
    *terminated = value != fmi2False;
    return status;
}

static int get_last_successful_time(const ssx_fmu_function *fn, void *instance, double *time)
{
    return (int)FMI2(fn, SLOT_GET_LAST_SUCCESSFUL_TIME, fmi2GetRealStatusTYPE)(
        instance, fmi2LastSuccessfulTime, time);
}

/* ------------------------------------------------------------------ Model Exchange */

static int set_time(const ssx_fmu_function *fn, void *instance, double time)
{
    return (int)FMI2(fn, SLOT_SET_TIME, fmi2SetTimeTYPE)(instance, time);
}

static int set_continuous_states(const ssx_fmu_function *fn, void *instance, const double *x,
                                 size_t nx)
{
    return (int)FMI2(fn, SLOT_SET_CONTINUOUS_STATES, fmi2SetContinuousStatesTYPE)(instance, x,
                                                                                 nx);
}

static int get_continuous_states(const ssx_fmu_function *fn, void *instance, double *x,
                                 size_t nx)
{
    return (int)FMI2(fn, SLOT_GET_CONTINUOUS_STATES, fmi2GetContinuousStatesTYPE)(instance, x,
                                                                                 nx);
}

static int get_derivatives(const ssx_fmu_function *fn, void *instance, double *dx, size_t nx)
{
    return (int)FMI2(fn, SLOT_GET_DERIVATIVES, fmi2GetDerivativesTYPE)(instance, dx, nx);
}

static int get_event_indicators(const ssx_fmu_function *fn, void *instance, double *z,
                                size_t nz)
{
    return (int)FMI2(fn, SLOT_GET_EVENT_INDICATORS, fmi2GetEventIndicatorsTYPE)(instance, z, nz);
}

static int get_nominals_of_continuous_states(const ssx_fmu_function *fn, void *instance,
                                             double *nominals, size_t nx)
{
    return (int)FMI2(fn, SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES,
                     fmi2GetNominalsOfContinuousStatesTYPE)(instance, nominals, nx);
}

static int enter_event_mode(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI2(fn, SLOT_ENTER_EVENT_MODE, fmi2EnterEventModeTYPE)(instance);
}

static int new_discrete_states(const ssx_fmu_function *fn, void *instance,
                               ssx_fmu_event_info *info)
{
    fmi2EventInfo event = {0};
    int status = (int)FMI2(fn, SLOT_NEW_DISCRETE_STATES, fmi2NewDiscreteStatesTYPE)(instance,
                                                                                   &event);
    *info = (ssx_fmu_event_info){
        .new_discrete_states_needed = event.newDiscreteStatesNeeded != fmi2False,
        .terminate_simulation = event.terminateSimulation != fmi2False,
        .nominals_changed = event.nominalsOfContinuousStatesChanged != fmi2False,
        .values_changed = event.valuesOfContinuousStatesChanged != fmi2False,
        .next_event_time_defined = event.nextEventTimeDefined != fmi2False,
        .next_event_time = event.nextEventTime,
    };
    return status;
}

static int enter_continuous_time_mode(const ssx_fmu_function *fn, void *instance)
{
    return (int)FMI2(fn, SLOT_ENTER_CONTINUOUS_TIME_MODE, fmi2EnterContinuousTimeModeTYPE)(
        instance);
}

static int completed_integrator_step(const ssx_fmu_function *fn, void *instance,
                                     int no_set_state_prior, int *enter_event_mode,
                                     int *terminate_simulation)
{
    fmi2Boolean enter = fmi2False, terminate = fmi2False;
    int status = (int)FMI2(fn, SLOT_COMPLETED_INTEGRATOR_STEP, fmi2CompletedIntegratorStepTYPE)(
        instance, no_set_state_prior ? fmi2True : fmi2False, &enter, &terminate);
    *enter_event_mode = enter != fmi2False;
    *terminate_simulation = terminate != fmi2False;
    return status;
}

/* The adapters both interfaces share. */
#define FMI2_ADAPTERS                                                                         \
    .version = "FMI 2.0", .status_names = fmi2_status_names,                                  \
    .context_size = sizeof(fmi2CallbackFunctions), .free_instance = free_instance,            \
    .setup_experiment = setup_experiment,                                                     \
    .enter_initialization_mode = enter_initialization_mode,                                   \
    .exit_initialization_mode = exit_initialization_mode, .terminate = terminate,             \
    .reset = reset, .get_real = get_real, .get_integer = get_integer,                         \
    .get_boolean = get_boolean, .set_real = set_real, .set_integer = set_integer,             \
    .set_boolean = set_boolean, .get_string = get_string, .set_string = set_string,           \
    .get_state = get_state, .set_state = set_state,                                            \
    .free_state = free_state, .serialized_state_size = serialized_state_size,                 \
    .serialize_state = serialize_state, .deserialize_state = deserialize_state,               \
    .directional_derivative = directional_derivative,                                          \
    .set_input_derivatives = set_input_derivatives,                                            \
    .get_output_derivatives = get_output_derivatives

const ssx_fmu_backend ssx_fmi2_model_exchange_backend = {
    FMI2_ADAPTERS,
    .standard = "FMI 2.0 Model Exchange",
    .interface = SSX_MODEL_EXCHANGE,
    .functions = fmi2_model_exchange_functions,
    .n_functions = sizeof fmi2_model_exchange_functions / sizeof fmi2_model_exchange_functions[0],
    .instantiate = instantiate_model_exchange,
    .set_time = set_time,
    .set_continuous_states = set_continuous_states,
    .get_continuous_states = get_continuous_states,
    .get_derivatives = get_derivatives,
    .get_event_indicators = get_event_indicators,
    .get_nominals_of_continuous_states = get_nominals_of_continuous_states,
    .enter_event_mode = enter_event_mode,
    .new_discrete_states = new_discrete_states,
    .enter_continuous_time_mode = enter_continuous_time_mode,
    .completed_integrator_step = completed_integrator_step,
};

const ssx_fmu_backend ssx_fmi2_backend = {
    FMI2_ADAPTERS,
    .standard = "FMI 2.0 Co-Simulation",
    .interface = SSX_CO_SIMULATION,
    .functions = fmi2_functions,
    .n_functions = sizeof fmi2_functions / sizeof fmi2_functions[0],
    .instantiate = instantiate,
    .do_step = do_step,
    .get_terminated = get_terminated,
    .get_last_successful_time = get_last_successful_time,
};
