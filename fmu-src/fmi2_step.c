/* fmi2DoStep and the Co-Simulation status queries. */
#include "fmi2_allowed.h"
#include "fmu_instance.h"
#include "fmu_log.h"
#include "fmu_step.h"

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2DoStep));
    if (inst == NULL)
        return fmi2Error;
    double start = inst->time;
    double t_end = currentCommunicationPoint + communicationStepSize;
    fmu_status status =
        fmu_do_step(inst, "fmi2DoStep", currentCommunicationPoint, communicationStepSize);
    if (status > FMU_WARNING || !(t_end > start) || fmu_stop_time(inst) > t_end)
        return fmi2_status(status);
    /* FMI 2.0 reports the model's request to stop as a discarded step (fmi2Terminated) */
    fmu_log(inst, FMU_DISCARD, LOG_STATUS_WARNING,
            "fmi2DoStep from t = %.17g to %.17g: the model asks to end the simulation at "
            "t = %.17g",
            currentCommunicationPoint, t_end, inst->time);
    return fmi2Discard;
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2CancelStep));
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_error(inst, "fmi2CancelStep: steps are never asynchronous in this FMU"));
}


fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetStatus));
    if (inst == NULL)
        return fmi2Error;
    if (s != fmi2DoStepStatus || value == NULL)
        return fmi2_status(fmu_error(inst, "fmi2GetStatus: only fmi2DoStepStatus is available"));
    *value = fmi2OK;
    return fmi2OK;
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetRealStatus));
    if (inst == NULL)
        return fmi2Error;
    if (s != fmi2LastSuccessfulTime || value == NULL)
        return fmi2_status(
            fmu_error(inst, "fmi2GetRealStatus: only fmi2LastSuccessfulTime is available"));
    *value = inst->time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)s;
    (void)value;
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetIntegerStatus));
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_error(inst, "fmi2GetIntegerStatus: no integer status is defined"));
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetBooleanStatus));
    if (inst == NULL)
        return fmi2Error;
    if (s != fmi2Terminated || value == NULL)
        return fmi2_status(fmu_error(inst,
                                     "fmi2GetBooleanStatus: only fmi2Terminated is available"));
    *value = inst->time >= fmu_stop_time(inst) ? fmi2True : fmi2False;
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)s;
    (void)value;
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetStringStatus));
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_error(inst, "fmi2GetStringStatus: no string status is defined"));
}
