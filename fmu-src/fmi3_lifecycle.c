/* FMI 3.0: creating, initializing, event and step mode, terminating, resetting and freeing, for
 * both interfaces (Model Exchange's own calls are in fmi3_model_exchange.c). */
#include <string.h>

#include "fmi3_allowed.h"
#include "fmi3_instance.h"
#include "fmu_evaluation.h"
#include "fmu_guid.h"
#include "fmu_log.h"
#include "fmu_model_exchange.h"
#include "fmu_step.h"

/* Hands the core's message to the importer's FMI 3.0 callback, which takes no instance name. */
static void forward_log(const fmu_logging_callbacks *callbacks, const char *instance_name,
                        fmu_status status, const char *category, const char *message)
{
    (void)instance_name;
    fmi3LogMessageCallback log_message = (fmi3LogMessageCallback)callbacks->logger;
    log_message(callbacks->environment, fmi3_status(status), category, message);
}

const char *fmi3GetVersion(void)
{
    return fmi3Version;
}

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3SetDebugLogging));
    if (inst == NULL)
        return fmi3Error;
    return fmi3_status(
        fmu_set_logging(&inst->core, "fmi3SetDebugLogging", loggingOn, nCategories, categories));
}

/* Why the FMU cannot be instantiated with these arguments, or NULL. */
static const char *refusal(fmi3String instanceName, fmi3String instantiationToken,
                           const char *guid, fmi3Boolean eventModeUsed,
                           const fmi3ValueReference requiredIntermediateVariables[],
                           size_t nRequiredIntermediateVariables)
{
    if (instanceName == NULL || instanceName[0] == '\0')
        return "the instance name is missing";
    if (instantiationToken == NULL || strcmp(instantiationToken, guid) != 0)
        return "the instantiation token does not match this FMU's";
    if (eventModeUsed && fmu_model.n_event_indicators == 0 && fmu_model.n_clocks == 0)
        return "eventModeUsed is true but this FMU has no event mode (hasEventMode=\"false\": "
               "the model has no internal events and no clocks)";
    if (nRequiredIntermediateVariables > 0 && requiredIntermediateVariables == NULL)
        return "requiredIntermediateVariables is NULL";
    for (size_t i = 0; i < nRequiredIntermediateVariables; ++i) {
        fmi3ValueReference vr = requiredIntermediateVariables[i];
        if (!(vr < fmu_model.n_variables && fmi3_intermediate_input(&fmu_model.variables[vr])))
            return "a required intermediate variable is not a continuous Float64 input (only "
                   "those provide intermediate access)";
    }
    return NULL;
}

/* The instance both interfaces start from, or NULL after reporting why through the importer's
 * callback; `function` names the call in messages. */
static fmi3_instance *create(const char *function, fmi3String instanceName,
                             fmi3String instantiationToken, fmi3Boolean loggingOn,
                             fmi3Boolean eventModeUsed,
                             const fmi3ValueReference requiredIntermediateVariables[],
                             size_t nRequiredIntermediateVariables,
                             fmi3InstanceEnvironment instanceEnvironment,
                             fmi3LogMessageCallback logMessage)
{
    /* A stand-in to report failures before the instance exists. */
    fmi3_instance reporter = {
        .core = {.name = (char *)(instanceName ? instanceName : "(unnamed)"),
                 .callbacks = {forward_log, (void (*)(void))logMessage, instanceEnvironment},
                 .logging_on = loggingOn,
                 .log_categories = LOG_ALL_CATEGORIES},
    };
    char guid[FMU_GUID_LENGTH];
    fmu_guid(guid);
    const char *reason = refusal(instanceName, instantiationToken, guid, eventModeUsed,
                                 requiredIntermediateVariables, nRequiredIntermediateVariables);
    if (reason != NULL) {
        fmu_error(&reporter.core, "%s: %s", function, reason);
        return NULL;
    }
    fmi3_instance *inst = (fmi3_instance *)fmu_instance_create(
        &reporter.core, sizeof(fmi3_instance), function);
    if (inst == NULL)
        return NULL;
    inst->environment = instanceEnvironment;
    return inst;
}

/* Intermediate update: the importer sets the inputs for time t. */
static void ask_importer_for_inputs(fmu_instance *core, double t)
{
    fmi3_instance *inst = (fmi3_instance *)core;
    fmi3Boolean early_return_requested = fmi3False;
    fmi3Float64 early_return_time = t;
    inst->intermediate_update(inst->environment, t, fmi3True, fmi3False, fmi3False, fmi3False,
                              &early_return_requested, &early_return_time);
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate)
{
    (void)resourcePath; /* the models need no resources */
    (void)visible;
    fmi3_instance *inst = create("fmi3InstantiateCoSimulation", instanceName, instantiationToken,
                                 loggingOn, eventModeUsed, requiredIntermediateVariables,
                                 nRequiredIntermediateVariables, instanceEnvironment, logMessage);
    if (inst == NULL)
        return NULL;
    /* Asked back only by an importer that named inputs it will set in intermediate update: the
     * call comes at every evaluation of the model inside a step. */
    if (intermediateUpdate != NULL && nRequiredIntermediateVariables > 0) {
        inst->intermediate_update = intermediateUpdate;
        inst->core.intermediate_update = ask_importer_for_inputs;
    }
    inst->event_mode_used = eventModeUsed;
    inst->early_return_allowed = earlyReturnAllowed;
    /* the importer handles internal events only when it can also be told of them early */
    inst->core.importer_handles_events =
        eventModeUsed && earlyReturnAllowed && !inst->core.model->events_at_step_end;
    return inst;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName,
                                          fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)resourcePath;
    (void)visible;
    fmi3_instance *inst = create("fmi3InstantiateModelExchange", instanceName, instantiationToken,
                                 loggingOn, fmi3False, NULL, 0, instanceEnvironment, logMessage);
    if (inst == NULL)
        return NULL;
    inst->model_exchange = 1;
    /* Model Exchange leaves initialization in event mode: the importer handles the initial
     * events */
    inst->core.running_phase = PHASE_EVENT;
    return inst;
}

void fmi3FreeInstance(fmi3Instance instance)
{
    fmi3_instance *inst = instance;
    fmu_instance_free(inst ? &inst->core : NULL);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    fmi3_instance *inst =
        fmi3_checked(instance, FMI3_CALL(fmi3EnterInitializationMode));
    if (inst == NULL)
        return fmi3Error;
    fmu_status status = fmu_setup_experiment(&inst->core, "fmi3EnterInitializationMode",
                                             toleranceDefined, tolerance, startTime,
                                             stopTimeDefined, stopTime);
    if (status == FMU_OK)
        inst->core.phase = PHASE_INITIALIZATION;
    return fmi3_status(status);
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    fmi3_instance *inst =
        fmi3_checked(instance, FMI3_CALL(fmi3ExitInitializationMode));
    if (inst == NULL)
        return fmi3Error;
    fmu_exit_initialization(&inst->core);
    inst->core.in_event_mode = inst->event_mode_used;
    return fmi3OK;
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3EnterEventMode));
    if (inst == NULL)
        return fmi3Error;
    if (inst->model_exchange) {
        inst->core.phase = PHASE_EVENT;
        return fmi3OK;
    }
    if (fmi3_mode_of(&inst->core) != MODE_STEP) {
        fmi3_refuse_in_mode(inst, "fmi3EnterEventMode");
        return fmi3Error;
    }
    if (!inst->event_mode_used)
        return fmi3_status(fmu_error(&inst->core, "fmi3EnterEventMode: the instance was "
                                                  "created with eventModeUsed = false"));
    inst->core.in_event_mode = 1;
    return fmi3OK;
}

/* The clocks set active since the last update tick now, with the inputs set at the tick. */
static void apply_clock_ticks(fmi3_instance *inst)
{
    const model_definition *model = inst->core.model;
    int any = 0;
    for (size_t i = 0; i < model->n_clocks; ++i)
        any |= inst->clock_active[i];
    if (!any)
        return;
    /* the partition reads the outputs and locals at the tick's time and states */
    if (inst->core.outputs_stale)
        fmu_refresh_outputs(&inst->core);
    model->clock_tick(inst->core.values, inst->core.time, inst->clock_active);
    for (size_t i = 0; i < model->n_clocks; ++i)
        inst->clock_active[i] = 0;
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined,
                                    fmi3Float64 *nextEventTime)
{
    fmi3_instance *inst =
        fmi3_checked(instance, FMI3_CALL(fmi3UpdateDiscreteStates));
    if (inst == NULL)
        return fmi3Error;
    if (!discreteStatesNeedUpdate || !terminateSimulation || !nominalsOfContinuousStatesChanged ||
        !valuesOfContinuousStatesChanged || !nextEventTimeDefined || !nextEventTime)
        return fmi3_status(
            fmu_error(&inst->core, "fmi3UpdateDiscreteStates: an output argument is NULL"));
    apply_clock_ticks(inst);
    /* the model's events and clock ticks change the state once; nothing else is discrete, so
     * one call settles */
    *discreteStatesNeedUpdate = false;
    *nominalsOfContinuousStatesChanged = false;
    if (inst->model_exchange) {
        fmu_discrete_update update;
        fmu_me_update_discrete_states(&inst->core, &update);
        *valuesOfContinuousStatesChanged = update.values_changed;
        *terminateSimulation = update.terminate;
        *nextEventTimeDefined = update.next_event_time_defined;
        *nextEventTime = update.next_event_time;
        return fmi3OK;
    }
    *valuesOfContinuousStatesChanged = fmu_apply_pending_events(&inst->core);
    *terminateSimulation = inst->core.time >= fmu_stop_time(&inst->core);
    *nextEventTimeDefined = false;
    *nextEventTime = 0.0;
    return fmi3OK;
}

fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3EnterStepMode));
    if (inst == NULL)
        return fmi3Error;
    if (inst->model_exchange)
        return fmi3_status(fmu_error(&inst->core, "fmi3EnterStepMode: a Model Exchange instance "
                                                  "has no Step Mode (fmi3EnterContinuousTimeMode "
                                                  "leaves Event Mode)"));
    if (inst->core.event_pending)
        return fmi3_status(fmu_error(&inst->core,
                                     "fmi3EnterStepMode: the internal event at t = %.17g is not "
                                     "applied yet (call fmi3UpdateDiscreteStates first)",
                                     inst->core.time));
    inst->core.in_event_mode = 0;
    return fmi3OK;
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3Terminate));
    if (inst == NULL)
        return fmi3Error;
    inst->core.phase = PHASE_TERMINATED;
    inst->core.in_event_mode = 0;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance instance)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3Reset));
    if (inst == NULL)
        return fmi3Error;
    fmu_reset(&inst->core);
    for (size_t i = 0; i < FMI3_MAX_CLOCKS; ++i)
        inst->clock_active[i] = 0;
    return fmi3OK;
}
