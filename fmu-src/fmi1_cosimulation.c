/* The FMI 1.0 Co-Simulation entry points over the version-neutral core: an instance is set up
 * and initialized by one call, fmiInitializeSlave, after its start values were set. */
#include "fmi1_entry.h"
#include "fmu_log.h"
#include "fmu_step.h"

FMI1_ENTRY(const char *, fmiGetTypesPlatform)(void)
{
    return "standard32";
}

FMI1_ENTRY(fmi1Component, fmiInstantiateSlave)(fmi1String instanceName, fmi1String fmuGUID,
                                               fmi1String fmuLocation, fmi1String mimeType,
                                               fmi1Real timeout, fmi1Boolean visible,
                                               fmi1Boolean interactive,
                                               fmi1CallbackFunctions functions,
                                               fmi1Boolean loggingOn)
{
    (void)fmuLocation; /* the models need no files */
    (void)mimeType;
    (void)timeout;
    (void)visible;
    (void)interactive;
    return fmi1_instantiate("fmiInstantiateSlave", instanceName, fmuGUID, functions.logger,
                            loggingOn);
}

FMI1_ENTRY(fmi1Status, fmiInitializeSlave)(fmi1Component c, fmi1Real tStart,
                                           fmi1Boolean StopTimeDefined, fmi1Real tStop)
{
    fmu_instance *inst = fmu_checked(c, "fmiInitializeSlave", PHASE_BIT(PHASE_INSTANTIATED));
    if (inst == NULL)
        return fmi1Error;
    /* FMI 1.0 sets the tolerance nowhere: the back-end's own */
    fmu_status status = fmu_setup_experiment(inst, "fmiInitializeSlave", 0, 0.0, tStart,
                                             StopTimeDefined != fmi1False, tStop);
    if (status > FMU_WARNING)
        return fmi1_status(status);
    inst->phase = PHASE_INITIALIZATION;
    fmu_exit_initialization(inst);
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiTerminateSlave)(fmi1Component c)
{
    fmu_instance *inst = fmu_checked(c, "fmiTerminateSlave", PHASES_INITIALIZED);
    if (inst == NULL)
        return fmi1Error;
    inst->phase = PHASE_TERMINATED;
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiResetSlave)(fmi1Component c)
{
    fmu_instance *inst = fmu_checked(c, "fmiResetSlave", PHASES_ANY);
    if (inst == NULL)
        return fmi1Error;
    fmu_reset(inst);
    return fmi1OK;
}

FMI1_ENTRY(void, fmiFreeSlaveInstance)(fmi1Component c)
{
    fmu_instance_free(c);
}

FMI1_ENTRY(fmi1Status, fmiSetRealInputDerivatives)(fmi1Component c, const fmi1ValueReference vr[],
                                                   size_t nvr, const fmi1Integer order[],
                                                   const fmi1Real value[])
{
    (void)vr;
    (void)order;
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmiSetRealInputDerivatives", PHASES_ANY);
    if (inst == NULL)
        return fmi1Error;
    return nvr == 0 ? fmi1OK
                    : fmi1_status(fmu_error(inst, "fmiSetRealInputDerivatives: inputs are "
                                                  "held, their derivatives are not used"));
}

FMI1_ENTRY(fmi1Status, fmiGetRealOutputDerivatives)(fmi1Component c,
                                                    const fmi1ValueReference vr[], size_t nvr,
                                                    const fmi1Integer order[], fmi1Real value[])
{
    (void)vr;
    (void)order;
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmiGetRealOutputDerivatives", PHASES_ANY);
    if (inst == NULL)
        return fmi1Error;
    return nvr == 0 ? fmi1OK
                    : fmi1_status(fmu_error(inst, "fmiGetRealOutputDerivatives: no output "
                                                  "derivatives are provided"));
}

FMI1_ENTRY(fmi1Status, fmiDoStep)(fmi1Component c, fmi1Real currentCommunicationPoint,
                                  fmi1Real communicationStepSize, fmi1Boolean newStep)
{
    (void)newStep; /* the FMU keeps no history to discard */
    fmu_instance *inst = fmu_checked(c, "fmiDoStep", PHASE_BIT(PHASE_STEP));
    if (inst == NULL)
        return fmi1Error;
    return fmi1_status(
        fmu_do_step(inst, "fmiDoStep", currentCommunicationPoint, communicationStepSize));
}

FMI1_ENTRY(fmi1Status, fmiCancelStep)(fmi1Component c)
{
    fmu_instance *inst = fmu_checked(c, "fmiCancelStep", PHASE_BIT(PHASE_STEP));
    if (inst == NULL)
        return fmi1Error;
    return fmi1_status(fmu_error(inst, "fmiCancelStep: steps are never asynchronous"));
}

FMI1_ENTRY(fmi1Status, fmiGetStatus)(fmi1Component c, const fmi1StatusKind s, fmi1Status *value)
{
    fmu_instance *inst = fmu_checked(c, "fmiGetStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi1Error;
    if (s != fmi1DoStepStatus || value == NULL)
        return fmi1_status(fmu_error(inst, "fmiGetStatus: only fmiDoStepStatus is available"));
    *value = fmi1OK;
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiGetRealStatus)(fmi1Component c, const fmi1StatusKind s,
                                         fmi1Real *value)
{
    fmu_instance *inst = fmu_checked(c, "fmiGetRealStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi1Error;
    if (s != fmi1LastSuccessfulTime || value == NULL)
        return fmi1_status(
            fmu_error(inst, "fmiGetRealStatus: only fmiLastSuccessfulTime is available"));
    *value = inst->time;
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiGetIntegerStatus)(fmi1Component c, const fmi1StatusKind s,
                                            fmi1Integer *value)
{
    (void)s;
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmiGetIntegerStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi1Error;
    return fmi1_status(fmu_error(inst, "fmiGetIntegerStatus: no integer status is defined"));
}

FMI1_ENTRY(fmi1Status, fmiGetBooleanStatus)(fmi1Component c, const fmi1StatusKind s,
                                            fmi1Boolean *value)
{
    (void)s;
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmiGetBooleanStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi1Error;
    return fmi1_status(fmu_error(inst, "fmiGetBooleanStatus: no boolean status is defined"));
}

FMI1_ENTRY(fmi1Status, fmiGetStringStatus)(fmi1Component c, const fmi1StatusKind s,
                                           fmi1String *value)
{
    (void)s;
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmiGetStringStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi1Error;
    return fmi1_status(fmu_error(inst, "fmiGetStringStatus: no string status is defined"));
}
