#include "fmu_step.h"

#include <math.h>

#include "fmu_interpolation.h"
#include "fmu_evaluation.h"
#include "fmu_log.h"
#include "fmu_solver.h"

/* A master's communication point may differ from the FMU's time by rounding, or by the
 * tol_time (1e-8 by default) that SysSimX skips after each event; the FMU then integrates from
 * its own time. Beyond this relative difference the two disagree and the step is refused. */
#define TIME_MATCH_TOLERANCE 1e-7

double fmu_stop_time(const fmu_instance *inst)
{
    return inst->model->termination_time != NULL ? inst->model->termination_time(inst->values)
                                                 : INFINITY;
}

static fmu_status refuse_step(fmu_instance *inst, const char *function, double t, double t_end,
                              const char *reason, step_refusal_kind kind)
{
    fmu_status status = fmu_refusal_status(inst, kind);
    fmu_log(inst, status, status == FMU_DISCARD ? LOG_STATUS_WARNING : LOG_STATUS_ERROR,
            "%s from t = %.17g to %.17g: %s", function, t, t_end, reason);
    return status;
}

fmu_status fmu_do_step(fmu_instance *inst, const char *function, double t, double h)
{
    if (!isfinite(h) || h < 0.0)
        return fmu_error(inst, "%s: communication step size %g is negative or not finite",
                         function, h);
    if (!isfinite(t))
        return fmu_error(inst, "%s: communication point %g is not finite", function, t);
    if (fabs(t - inst->time) > TIME_MATCH_TOLERANCE * fmax(1.0, fabs(inst->time)))
        return fmu_error(inst, "%s: communication point %.17g differs from the FMU's time %.17g",
                         function, t, inst->time);
    double t_end = t + h;
    if (t_end <= inst->time) {
        fmu_refresh_outputs(inst);
        return FMU_OK;
    }
    if (inst->model->step_refusal != NULL) {
        step_refusal_kind kind = STEP_FAILS;
        const char *reason = inst->model->step_refusal(inst->values, t_end, &kind);
        if (reason != NULL)
            return refuse_step(inst, function, t, t_end, reason, kind);
    }
    /* a model that asks to stop inside the step is integrated up to that time only */
    double t_until = fmin(t_end, fmu_stop_time(inst));
    fmu_status status = FMU_OK;
    if (t_until > inst->time) {
        fmu_inputs_begin_step(inst);
        status = fmu_solver_step(inst, t_until);
        fmu_inputs_end_step(inst, inst->time);
    }
    fmu_refresh_outputs(inst);
    return status;
}
