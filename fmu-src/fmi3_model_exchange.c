/* The FMI 3.0 Model Exchange entry points: each checks the call is allowed in the instance's
 * mode, and on a Model Exchange instance only, then runs the version-neutral Model Exchange
 * core (fmu_model_exchange.c) that fmi2_model_exchange.c runs too. Event Mode (entering it,
 * fmi3UpdateDiscreteStates) is shared with Co-Simulation in fmi3_lifecycle.c. */
#include "fmi3_allowed.h"
#include "fmi3_instance.h"
#include "fmu_log.h"
#include "fmu_model_exchange.h"

/* The instance when it is a Model Exchange one in one of the modes in `allowed`; otherwise
 * logs why and returns NULL. */
static fmi3_instance *me_checked(fmi3Instance instance, const char *function, unsigned allowed)
{
    fmi3_instance *inst = fmi3_checked(instance, function, allowed);
    if (inst != NULL && !inst->model_exchange) {
        fmu_error(&inst->core, "%s: the instance was made by fmi3InstantiateCoSimulation, not "
                               "for Model Exchange", function);
        return NULL;
    }
    return inst;
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{
    fmi3_instance *inst = me_checked(instance, FMI3_CALL(fmi3SetTime));
    return inst != NULL ? fmi3_status(fmu_me_set_time(&inst->core, "fmi3SetTime", time))
                        : fmi3Error;
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    fmi3_instance *inst =
        me_checked(instance, FMI3_CALL(fmi3SetContinuousStates));
    return inst != NULL ? fmi3_status(fmu_me_set_states(&inst->core, "fmi3SetContinuousStates",
                                                        continuousStates, nContinuousStates))
                        : fmi3Error;
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    fmi3_instance *inst = me_checked(instance, FMI3_CALL(fmi3GetContinuousStates));
    return inst != NULL ? fmi3_status(fmu_me_get_states(&inst->core, "fmi3GetContinuousStates",
                                                        continuousStates, nContinuousStates))
                        : fmi3Error;
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
    fmi3_instance *inst =
        me_checked(instance, FMI3_CALL(fmi3GetContinuousStateDerivatives));
    return inst != NULL
               ? fmi3_status(fmu_me_derivatives(&inst->core, "fmi3GetContinuousStateDerivatives",
                                                derivatives, nContinuousStates))
               : fmi3Error;
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[],
                                  size_t nEventIndicators)
{
    fmi3_instance *inst = me_checked(instance, FMI3_CALL(fmi3GetEventIndicators));
    return inst != NULL ? fmi3_status(fmu_me_event_indicators(&inst->core,
                                                              "fmi3GetEventIndicators",
                                                              eventIndicators, nEventIndicators))
                        : fmi3Error;
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[],
                                             size_t nContinuousStates)
{
    fmi3_instance *inst = me_checked(instance, FMI3_CALL(fmi3GetNominalsOfContinuousStates));
    return inst != NULL
               ? fmi3_status(fmu_me_nominals(&inst->core, "fmi3GetNominalsOfContinuousStates",
                                             nominals, nContinuousStates))
               : fmi3Error;
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators)
{
    fmi3_instance *inst = me_checked(instance, FMI3_CALL(fmi3GetNumberOfEventIndicators));
    if (inst == NULL)
        return fmi3Error;
    if (nEventIndicators == NULL)
        return fmi3_status(
            fmu_error(&inst->core, "fmi3GetNumberOfEventIndicators: the result pointer is NULL"));
    *nEventIndicators = inst->core.model->n_event_indicators;
    return fmi3OK;
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates)
{
    fmi3_instance *inst = me_checked(instance, FMI3_CALL(fmi3GetNumberOfContinuousStates));
    if (inst == NULL)
        return fmi3Error;
    if (nContinuousStates == NULL)
        return fmi3_status(fmu_error(
            &inst->core, "fmi3GetNumberOfContinuousStates: the result pointer is NULL"));
    *nContinuousStates = inst->core.model->n_states;
    return fmi3OK;
}

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{
    fmi3_instance *inst =
        me_checked(instance, FMI3_CALL(fmi3EnterContinuousTimeMode));
    if (inst == NULL)
        return fmi3Error;
    inst->core.phase = PHASE_CONTINUOUS_TIME;
    return fmi3OK;
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode,
                                       fmi3Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint; /* the FMU keeps no history to discard */
    fmi3_instance *inst =
        me_checked(instance, FMI3_CALL(fmi3CompletedIntegratorStep));
    if (inst == NULL)
        return fmi3Error;
    if (enterEventMode == NULL || terminateSimulation == NULL)
        return fmi3_status(
            fmu_error(&inst->core, "fmi3CompletedIntegratorStep: a result pointer is NULL"));
    /* no step events: every event is a state event (an indicator) or a time event */
    *enterEventMode = fmi3False;
    *terminateSimulation = fmu_me_terminates(&inst->core) ? fmi3True : fmi3False;
    return fmi3OK;
}
