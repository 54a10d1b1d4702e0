/* The Model Exchange interface: the importer integrates the model's equations itself. It sets
 * the time and the states, reads the derivatives and the event indicators (its root functions),
 * and calls event mode where an indicator changed sign or a time event is due; event mode
 * applies the model's own event handling. Which call is allowed when is for the entry points
 * of each FMI version (fmi2_model_exchange.c, fmi3_model_exchange.c) to check. */
#include "fmu_model_exchange.h"

#include <math.h>
#include <string.h>

#include "fmu_evaluation.h"
#include "fmu_log.h"

/* Every model quantity is of order one (model.h): the importer scales its tolerances by this. */
#define STATE_NOMINAL 1.0

static fmu_status check_vector(const fmu_instance *inst, const char *function, const void *array,
                               size_t given, size_t expected, const char *what)
{
    if (given != expected)
        return fmu_error(inst, "%s: %zu %s requested, the model has %zu", function, given, what,
                         expected);
    if (given > 0 && array == NULL)
        return fmu_error(inst, "%s: the array of %s is NULL", function, what);
    return FMU_OK;
}

/* In initialization mode the states follow their start parameters (fmu_refresh_outputs);
 * afterwards they are what the importer set. */
static void settle(fmu_instance *inst)
{
    if (inst->outputs_stale && inst->phase == PHASE_INITIALIZATION)
        fmu_refresh_outputs(inst);
}

/* When the model asks to end the simulation (INFINITY when it never does). */
static double termination_time(const fmu_instance *inst)
{
    return inst->model->termination_time != NULL ? inst->model->termination_time(inst->values)
                                                 : INFINITY;
}

int fmu_me_terminates(const fmu_instance *inst)
{
    return inst->time >= termination_time(inst);
}

fmu_status fmu_me_set_time(fmu_instance *inst, const char *function, double time)
{
    if (!isfinite(time))
        return fmu_error(inst, "%s: time %g is not finite", function, time);
    /* A model that refuses a step ending at some time refuses to be evaluated there: models
     * without states are evaluated through their time alone. */
    if (inst->model->step_refusal != NULL) {
        step_refusal_kind kind = STEP_FAILS;
        const char *reason = inst->model->step_refusal(inst->values, time, &kind);
        if (reason != NULL) {
            fmu_status status = fmu_refusal_status(inst, kind);
            fmu_log(inst, status, status == FMU_DISCARD ? LOG_STATUS_WARNING : LOG_STATUS_ERROR,
                    "%s to t = %.17g: %s", function, time, reason);
            return status;
        }
    }
    inst->time = time;
    inst->outputs_stale = 1;
    return FMU_OK;
}

fmu_status fmu_me_set_states(fmu_instance *inst, const char *function, const double *x,
                             size_t nx)
{
    if (check_vector(inst, function, x, nx, inst->model->n_states, "states") != FMU_OK)
        return FMU_ERROR;
    for (size_t i = 0; i < nx; ++i)
        if (isnan(x[i]))
            return fmu_error(inst, "%s: state %zu (%s) is NaN", function, i,
                             inst->model->variables[inst->model->state_vrs[i]].name);
    memcpy(inst->x, x, nx * sizeof(double));
    inst->outputs_stale = 1;
    return FMU_OK;
}

fmu_status fmu_me_get_states(fmu_instance *inst, const char *function, double *x, size_t nx)
{
    if (check_vector(inst, function, x, nx, inst->model->n_states, "states") != FMU_OK)
        return FMU_ERROR;
    settle(inst);
    if (nx > 0)
        memcpy(x, inst->x, nx * sizeof(double));
    return FMU_OK;
}

fmu_status fmu_me_derivatives(fmu_instance *inst, const char *function, double *dx, size_t nx)
{
    if (check_vector(inst, function, dx, nx, inst->model->n_states, "derivatives") != FMU_OK)
        return FMU_ERROR;
    settle(inst);
    if (nx > 0)
        inst->model->derivatives(inst->values, inst->time, inst->x, dx);
    return FMU_OK;
}

fmu_status fmu_me_event_indicators(fmu_instance *inst, const char *function, double *z,
                                   size_t nz)
{
    if (check_vector(inst, function, z, nz, inst->model->n_event_indicators,
                     "event indicators") != FMU_OK)
        return FMU_ERROR;
    settle(inst);
    fmu_event_indicators(inst, z);
    /* An event can leave an indicator at exactly 0 (a bounce puts the ball on the floor), and a
     * root finder reports no crossing when it leaves 0 upwards. The importer asks for the
     * indicators on the trajectory it accepts, so a positive value seen here arms the next
     * fall, as the model's own back-ends do with falling-only root directions. */
    if (inst->phase == PHASE_CONTINUOUS_TIME)
        for (size_t i = 0; i < nz; ++i)
            if (z[i] > 0.0)
                inst->z_previous[i] = z[i];
    return FMU_OK;
}

fmu_status fmu_me_nominals(fmu_instance *inst, const char *function, double *nominals,
                           size_t nx)
{
    if (check_vector(inst, function, nominals, nx, inst->model->n_states, "nominals") != FMU_OK)
        return FMU_ERROR;
    for (size_t i = 0; i < nx; ++i)
        nominals[i] = STATE_NOMINAL;
    return FMU_OK;
}

/* Applies the events of the indicators that fell from > 0 to <= 0 since the last event mode;
 * returns whether the states changed. The indicators after it are the next comparison's. */
static int handle_state_events(fmu_instance *inst)
{
    const model_definition *model = inst->model;
    size_t n = model->n_event_indicators;
    if (n == 0)
        return 0;
    fmu_event_indicators(inst, inst->z_after);
    int any = 0;
    for (size_t i = 0; i < n; ++i) {
        inst->fired[i] = inst->z_previous[i] > 0.0 && inst->z_after[i] <= 0.0;
        any |= inst->fired[i];
    }
    int changed = 0;
    if (any) {
        memcpy(inst->dx, inst->x, model->n_states * sizeof(double)); /* dx: scratch */
        fmu_handle_events(inst, inst->time, inst->x);
        changed = memcmp(inst->dx, inst->x, model->n_states * sizeof(double)) != 0;
        inst->outputs_stale = 1;
    }
    fmu_event_indicators(inst, inst->z_previous);
    return changed;
}

void fmu_me_update_discrete_states(fmu_instance *inst, fmu_discrete_update *update)
{
    update->values_changed = handle_state_events(inst);
    double next = inst->model->next_time_event != NULL
                      ? inst->model->next_time_event(inst->values, inst->time)
                      : INFINITY;
    double stop = termination_time(inst);
    update->terminate = inst->time >= stop;
    if (update->terminate)
        fmu_log(inst, FMU_OK, LOG_EVENTS, "the model asks to end the simulation at t = %.17g",
                inst->time);
    else
        next = fmin(next, stop);
    update->next_event_time_defined = isfinite(next);
    update->next_event_time = isfinite(next) ? next : 0.0;
}
