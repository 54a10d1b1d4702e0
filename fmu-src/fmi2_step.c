/* fmi2DoStep and the Co-Simulation status queries. */
#include <math.h>

#include "fmu_instance.h"
#include "fmu_log.h"
#include "fmu_solver.h"

/* A master's communication point may differ from the FMU's time by rounding, or by the
 * tol_time (1e-8 by default) that SysSimX skips after each event; the FMU then integrates from
 * its own time. Beyond this relative difference the two disagree and the step is refused. */
#define TIME_MATCH_TOLERANCE 1e-7

/* When the model asks to stop (INFINITY when it never does). */
static double stop_time(const fmu_instance *inst)
{
    return inst->model->termination_time != NULL ? inst->model->termination_time(inst->values)
                                                 : INFINITY;
}

static fmi2Status refuse_step(fmu_instance *inst, double t, double t_end, const char *reason,
                              step_refusal_kind kind)
{
    fmi2Status status = fmu_refusal_status(inst, kind);
    fmu_log(inst, status, status == fmi2Discard ? LOG_STATUS_WARNING : LOG_STATUS_ERROR,
            "fmi2DoStep from t = %.17g to %.17g: %s", t, t_end, reason);
    return status;
}

/* A model that asks to stop inside the step is integrated up to that time only. */
static fmi2Status step_until_stop(fmu_instance *inst, double t, double t_end)
{
    double t_stop = stop_time(inst);
    fmi2Status status = fmi2OK;
    if (fmin(t_end, t_stop) > inst->time)
        status = fmu_solver_step(inst, fmin(t_end, t_stop));
    fmu_refresh_outputs(inst);
    if (status > fmi2Warning || t_stop > t_end)
        return status;
    fmu_log(inst, fmi2Discard, LOG_STATUS_WARNING,
            "fmi2DoStep from t = %.17g to %.17g: the model asks to end the simulation at "
            "t = %.17g",
            t, t_end, inst->time);
    return fmi2Discard;
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    fmu_instance *inst = fmu_checked(c, "fmi2DoStep", PHASE_BIT(PHASE_STEP));
    if (inst == NULL)
        return fmi2Error;
    double t = currentCommunicationPoint;
    double h = communicationStepSize;
    if (!isfinite(h) || h < 0.0)
        return fmu_error(inst, "fmi2DoStep: communication step size %g is negative or not finite",
                         h);
    if (!isfinite(t))
        return fmu_error(inst, "fmi2DoStep: communication point %g is not finite", t);
    if (fabs(t - inst->time) > TIME_MATCH_TOLERANCE * fmax(1.0, fabs(inst->time)))
        return fmu_error(inst,
                         "fmi2DoStep: communication point %.17g differs from the FMU's time "
                         "%.17g",
                         t, inst->time);
    double t_end = t + h;
    if (t_end <= inst->time) {
        /* a zero step (or one that ends where the FMU already is) only refreshes outputs */
        fmu_refresh_outputs(inst);
        return fmi2OK;
    }
    if (inst->model->step_refusal != NULL) {
        step_refusal_kind kind = STEP_FAILS;
        const char *reason = inst->model->step_refusal(inst->values, t_end, &kind);
        if (reason != NULL)
            return refuse_step(inst, t, t_end, reason, kind);
    }
    if (inst->model->termination_time != NULL)
        return step_until_stop(inst, t, t_end);
    fmi2Status status = fmu_solver_step(inst, t_end);
    fmu_refresh_outputs(inst);
    return status;
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    fmu_instance *inst = fmu_checked(c, "fmi2CancelStep", PHASE_BIT(PHASE_STEP));
    if (inst == NULL)
        return fmi2Error;
    return fmu_error(inst, "fmi2CancelStep: steps are never asynchronous in this FMU");
}


fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    fmu_instance *inst = fmu_checked(c, "fmi2GetStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi2Error;
    if (s != fmi2DoStepStatus || value == NULL)
        return fmu_error(inst, "fmi2GetStatus: only fmi2DoStepStatus is available");
    *value = fmi2OK;
    return fmi2OK;
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    fmu_instance *inst = fmu_checked(c, "fmi2GetRealStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi2Error;
    if (s != fmi2LastSuccessfulTime || value == NULL)
        return fmu_error(inst, "fmi2GetRealStatus: only fmi2LastSuccessfulTime is available");
    *value = inst->time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)s;
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmi2GetIntegerStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi2Error;
    return fmu_error(inst, "fmi2GetIntegerStatus: no integer status is defined");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    fmu_instance *inst = fmu_checked(c, "fmi2GetBooleanStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi2Error;
    if (s != fmi2Terminated || value == NULL)
        return fmu_error(inst, "fmi2GetBooleanStatus: only fmi2Terminated is available");
    *value = inst->time >= stop_time(inst) ? fmi2True : fmi2False;
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)s;
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmi2GetStringStatus", PHASES_STATUS);
    if (inst == NULL)
        return fmi2Error;
    return fmu_error(inst, "fmi2GetStringStatus: no string status is defined");
}
