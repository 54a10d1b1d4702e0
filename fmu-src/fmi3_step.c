/* fmi3DoStep. The model's internal events either are handled inside the step (as in FMI 2.0)
 * or, with event mode and early return, end the step at the event: the importer then applies it
 * in Event Mode. A model that asks to stop ends the step at that time with terminateSimulation;
 * a step the model refuses fails, is discarded or is fatal, as the model says. */
#include "fmi3_allowed.h"
#include "fmi3_instance.h"
#include "fmu_log.h"
#include "fmu_step.h"

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    fmi3_instance *self = fmi3_checked(instance, FMI3_CALL(fmi3DoStep));
    if (self == NULL)
        return fmi3Error;
    fmu_instance *inst = &self->core;
    if (!eventHandlingNeeded || !terminateSimulation || !earlyReturn || !lastSuccessfulTime)
        return fmi3_status(fmu_error(inst, "fmi3DoStep: an output argument is NULL"));
    if (inst->event_pending)
        return fmi3_status(fmu_error(inst,
                                     "fmi3DoStep: the internal event at t = %.17g is not handled "
                                     "yet (call fmi3EnterEventMode and fmi3UpdateDiscreteStates "
                                     "first)",
                                     inst->time));
    double t_end = currentCommunicationPoint + communicationStepSize;
    size_t n_indicators = inst->model->n_event_indicators;
    for (size_t i = 0; i < n_indicators; ++i)
        inst->fired_in_step[i] = 0;
    fmu_status status =
        fmu_do_step(inst, "fmi3DoStep", currentCommunicationPoint, communicationStepSize);
    int completed = status <= FMU_WARNING;
    if (completed && self->event_mode_used && inst->model->events_at_step_end) {
        /* the events handled inside the step tick their output clocks at its end */
        int any = 0;
        for (size_t i = 0; i < n_indicators; ++i) {
            inst->fired[i] = inst->fired_in_step[i];
            any |= inst->fired[i];
        }
        if (any)
            inst->event_pending = EVENTS_HANDLED_IN_STEP;
    }
    *eventHandlingNeeded = completed && inst->event_pending;
    *terminateSimulation = completed && inst->time >= fmu_stop_time(inst);
    *earlyReturn = completed && self->early_return_allowed && inst->time < t_end;
    *lastSuccessfulTime = inst->time;
    return fmi3_status(status);
}
