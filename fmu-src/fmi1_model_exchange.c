/* The FMI 1.0 Model Exchange entry points over the version-neutral core. FMI 1.0 has no
 * event mode to enter or leave: fmiInitialize and fmiEventUpdate each run one event iteration
 * of the core (which settles in one pass) and return to continuous time. */
#include <math.h>

#include "fmi1_entry.h"
#include "fmu_log.h"
#include "fmu_model_exchange.h"

/* FMI 1.0 Model Exchange passes three callbacks by value (fmi1Functions.h's struct is the
 * Co-Simulation one, with stepFinished). */
typedef struct {
    fmi1CallbackLogger logger;
    fmi1CallbackAllocateMemory allocateMemory;
    fmi1CallbackFreeMemory freeMemory;
} fmi1_model_callbacks;

/* After initialization an FMI 1.0 model may be evaluated at any time, events and continuous
 * time alike. */
#define PHASES_FMI1_RUNNING PHASES_EVENT_OR_CONTINUOUS

FMI1_ENTRY(const char *, fmiGetModelTypesPlatform)(void)
{
    return "standard32";
}

FMI1_ENTRY(fmi1Component, fmiInstantiateModel)(fmi1String instanceName, fmi1String GUID,
                                               fmi1_model_callbacks functions,
                                               fmi1Boolean loggingOn)
{
    fmu_instance *inst = fmi1_instantiate("fmiInstantiateModel", instanceName, GUID,
                                          functions.logger, loggingOn);
    if (inst != NULL)
        inst->running_phase = PHASE_EVENT; /* fmiInitialize runs the first event iteration */
    return inst;
}

FMI1_ENTRY(void, fmiFreeModelInstance)(fmi1Component c)
{
    fmu_instance_free(c);
}

FMI1_ENTRY(fmi1Status, fmiSetTime)(fmi1Component c, fmi1Real time)
{
    fmu_instance *inst = fmu_checked(c, "fmiSetTime",
                                     PHASE_BIT(PHASE_INSTANTIATED) | PHASES_FMI1_RUNNING);
    if (inst == NULL)
        return fmi1Error;
    if (inst->phase != PHASE_INSTANTIATED)
        return fmi1_status(fmu_me_set_time(inst, "fmiSetTime", time));
    if (!isfinite(time)) /* the start time, which fmiInitialize sets up */
        return fmi1_status(fmu_error(inst, "fmiSetTime: time %g is not finite", time));
    inst->time = time;
    return fmi1OK;
}

static void tell(const fmu_discrete_update *update, fmi1EventInfo *eventInfo)
{
    eventInfo->iterationConverged = fmi1True; /* handling an event never fires another */
    eventInfo->stateValueReferencesChanged = fmi1False;
    eventInfo->stateValuesChanged = update->values_changed ? fmi1True : fmi1False;
    eventInfo->terminateSimulation = update->terminate ? fmi1True : fmi1False;
    eventInfo->upcomingTimeEvent = update->next_event_time_defined ? fmi1True : fmi1False;
    eventInfo->nextEventTime = update->next_event_time;
}

FMI1_ENTRY(fmi1Status, fmiInitialize)(fmi1Component c, fmi1Boolean toleranceControlled,
                                      fmi1Real relativeTolerance, fmi1EventInfo *eventInfo)
{
    fmu_instance *inst = fmu_checked(c, "fmiInitialize", PHASE_BIT(PHASE_INSTANTIATED));
    if (inst == NULL)
        return fmi1Error;
    if (eventInfo == NULL)
        return fmi1_status(fmu_error(inst, "fmiInitialize: the event info pointer is NULL"));
    fmu_status status = fmu_setup_experiment(inst, "fmiInitialize",
                                             toleranceControlled != fmi1False,
                                             relativeTolerance, inst->time, 0, 0.0);
    if (status > FMU_WARNING)
        return fmi1_status(status);
    inst->phase = PHASE_INITIALIZATION;
    fmu_exit_initialization(inst);
    fmu_discrete_update update;
    fmu_me_update_discrete_states(inst, &update);
    tell(&update, eventInfo);
    inst->phase = PHASE_CONTINUOUS_TIME;
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiEventUpdate)(fmi1Component c, fmi1Boolean intermediateResults,
                                       fmi1EventInfo *eventInfo)
{
    (void)intermediateResults; /* one pass converges: there is nothing in between */
    fmu_instance *inst = fmu_checked(c, "fmiEventUpdate", PHASES_FMI1_RUNNING);
    if (inst == NULL)
        return fmi1Error;
    if (eventInfo == NULL)
        return fmi1_status(fmu_error(inst, "fmiEventUpdate: the event info pointer is NULL"));
    inst->phase = PHASE_EVENT;
    fmu_discrete_update update;
    fmu_me_update_discrete_states(inst, &update);
    tell(&update, eventInfo);
    inst->phase = PHASE_CONTINUOUS_TIME;
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiSetContinuousStates)(fmi1Component c, const fmi1Real x[], size_t nx)
{
    fmu_instance *inst = fmu_checked(c, "fmiSetContinuousStates", PHASES_FMI1_RUNNING);
    return inst != NULL ? fmi1_status(fmu_me_set_states(inst, "fmiSetContinuousStates", x, nx))
                        : fmi1Error;
}

FMI1_ENTRY(fmi1Status, fmiGetContinuousStates)(fmi1Component c, fmi1Real states[], size_t nx)
{
    fmu_instance *inst = fmu_checked(c, "fmiGetContinuousStates", PHASES_MODEL_EVALUATION);
    return inst != NULL
               ? fmi1_status(fmu_me_get_states(inst, "fmiGetContinuousStates", states, nx))
               : fmi1Error;
}

FMI1_ENTRY(fmi1Status, fmiGetDerivatives)(fmi1Component c, fmi1Real derivatives[], size_t nx)
{
    fmu_instance *inst = fmu_checked(c, "fmiGetDerivatives", PHASES_MODEL_EVALUATION);
    return inst != NULL
               ? fmi1_status(fmu_me_derivatives(inst, "fmiGetDerivatives", derivatives, nx))
               : fmi1Error;
}

FMI1_ENTRY(fmi1Status, fmiGetEventIndicators)(fmi1Component c, fmi1Real eventIndicators[],
                                              size_t ni)
{
    fmu_instance *inst = fmu_checked(c, "fmiGetEventIndicators", PHASES_MODEL_EVALUATION);
    return inst != NULL ? fmi1_status(fmu_me_event_indicators(inst, "fmiGetEventIndicators",
                                                              eventIndicators, ni))
                        : fmi1Error;
}

FMI1_ENTRY(fmi1Status, fmiGetNominalContinuousStates)(fmi1Component c, fmi1Real x_nominal[],
                                                      size_t nx)
{
    fmu_instance *inst = fmu_checked(c, "fmiGetNominalContinuousStates", PHASES_NOMINALS);
    return inst != NULL ? fmi1_status(fmu_me_nominals(inst, "fmiGetNominalContinuousStates",
                                                      x_nominal, nx))
                        : fmi1Error;
}

FMI1_ENTRY(fmi1Status, fmiGetStateValueReferences)(fmi1Component c, fmi1ValueReference vrx[],
                                                   size_t nx)
{
    fmu_instance *inst = fmu_checked(c, "fmiGetStateValueReferences", PHASES_ANY);
    if (inst == NULL)
        return fmi1Error;
    if (nx != inst->model->n_states || (nx > 0 && vrx == NULL))
        return fmi1_status(fmu_error(inst, "fmiGetStateValueReferences: nx is %zu, the model "
                                           "has %zu states", nx, inst->model->n_states));
    for (size_t i = 0; i < nx; ++i)
        vrx[i] = inst->model->state_vrs[i];
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiCompletedIntegratorStep)(fmi1Component c, fmi1Boolean *callEventUpdate)
{
    fmu_instance *inst =
        fmu_checked(c, "fmiCompletedIntegratorStep", PHASE_BIT(PHASE_CONTINUOUS_TIME));
    if (inst == NULL)
        return fmi1Error;
    if (callEventUpdate == NULL)
        return fmi1_status(
            fmu_error(inst, "fmiCompletedIntegratorStep: the result pointer is NULL"));
    *callEventUpdate = fmi1False; /* no step events */
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiTerminate)(fmi1Component c)
{
    fmu_instance *inst = fmu_checked(c, "fmiTerminate", PHASES_INITIALIZED);
    if (inst == NULL)
        return fmi1Error;
    inst->phase = PHASE_TERMINATED;
    return fmi1OK;
}
