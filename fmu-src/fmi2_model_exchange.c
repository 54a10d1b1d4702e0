/* The FMI 2.0 Model Exchange entry points: each checks the call is allowed in the instance's
 * phase (fmu_instance.h) and runs the version-neutral Model Exchange core
 * (fmu_model_exchange.c). */
#include "fmi2_allowed.h"
#include "fmu_instance.h"
#include "fmu_log.h"
#include "fmu_model_exchange.h"

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2SetTime));
    return inst != NULL ? fmu_me_set_time(inst, "fmi2SetTime", time) : fmi2Error;
}

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx)
{
    fmu_instance *inst =
        fmu_checked(c, FMI2_CALL(fmi2SetContinuousStates));
    return inst != NULL ? fmu_me_set_states(inst, "fmi2SetContinuousStates", x, nx) : fmi2Error;
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetContinuousStates));
    return inst != NULL ? fmu_me_get_states(inst, "fmi2GetContinuousStates", x, nx) : fmi2Error;
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetDerivatives));
    return inst != NULL ? fmu_me_derivatives(inst, "fmi2GetDerivatives", derivatives, nx)
                        : fmi2Error;
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real eventIndicators[], size_t ni)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetEventIndicators));
    return inst != NULL
               ? fmu_me_event_indicators(inst, "fmi2GetEventIndicators", eventIndicators, ni)
               : fmi2Error;
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x_nominal[], size_t nx)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetNominalsOfContinuousStates));
    return inst != NULL
               ? fmu_me_nominals(inst, "fmi2GetNominalsOfContinuousStates", x_nominal, nx)
               : fmi2Error;
}

fmi2Status fmi2EnterEventMode(fmi2Component c)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2EnterEventMode));
    if (inst == NULL)
        return fmi2Error;
    inst->phase = PHASE_EVENT;
    return fmi2OK;
}

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *eventInfo)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2NewDiscreteStates));
    if (inst == NULL)
        return fmi2Error;
    if (eventInfo == NULL)
        return fmi2_status(fmu_error(inst,
                                     "fmi2NewDiscreteStates: the event info pointer is NULL"));
    fmu_discrete_update update;
    fmu_me_update_discrete_states(inst, &update);
    /* one pass reaches the new discrete state: handling an event never fires another */
    eventInfo->newDiscreteStatesNeeded = fmi2False;
    eventInfo->terminateSimulation = update.terminate ? fmi2True : fmi2False;
    eventInfo->nominalsOfContinuousStatesChanged = fmi2False;
    eventInfo->valuesOfContinuousStatesChanged = update.values_changed ? fmi2True : fmi2False;
    eventInfo->nextEventTimeDefined = update.next_event_time_defined ? fmi2True : fmi2False;
    eventInfo->nextEventTime = update.next_event_time;
    return fmi2OK;
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2EnterContinuousTimeMode));
    if (inst == NULL)
        return fmi2Error;
    inst->phase = PHASE_CONTINUOUS_TIME;
    return fmi2OK;
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c,
                                       fmi2Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi2Boolean *enterEventMode,
                                       fmi2Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint; /* the FMU keeps no history to discard */
    fmu_instance *inst =
        fmu_checked(c, FMI2_CALL(fmi2CompletedIntegratorStep));
    if (inst == NULL)
        return fmi2Error;
    if (enterEventMode == NULL || terminateSimulation == NULL)
        return fmi2_status(fmu_error(inst,
                                     "fmi2CompletedIntegratorStep: a result pointer is NULL"));
    /* no step events: every event is a state event (an indicator) or a time event */
    *enterEventMode = fmi2False;
    *terminateSimulation = fmu_me_terminates(inst) ? fmi2True : fmi2False;
    return fmi2OK;
}
