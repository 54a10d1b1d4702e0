#include "fmu_instance.h"

#include <stddef.h>

#include "fmu_log.h"
#include "fmu_solver.h"

static const char *const phase_names[] = {
    "instantiated", "initialization mode",  "step mode",
    "event mode",   "continuous-time mode", "terminated",
    "the fatal state (after fmi2Fatal)"};

const char *fmu_phase_name(fmu_phase phase)
{
    return phase_names[phase];
}

fmu_instance *fmu_refuse_in_phase(fmu_instance *inst, const char *function)
{
    fmu_error(inst, "%s is not allowed in %s", function, fmu_phase_name(inst->phase));
    return NULL;
}

double fmu_solver_parameter(const fmu_instance *inst, size_t i)
{
    return inst->values[inst->model->n_variables + i];
}

void fmu_apply_start_values(fmu_instance *inst)
{
    for (size_t vr = 0; vr < inst->n_variables; ++vr)
        inst->values[vr] = fmu_variable(inst, (fmi2ValueReference)vr)->start;
    inst->time = 0.0;
    inst->tolerance_defined = 0;
    inst->tolerance = 0.0;
    if (inst->model->n_states > 0)
        inst->model->initial_states(inst->values, inst->x);
    fmu_refresh_outputs(inst);
}

void fmu_refresh_outputs(fmu_instance *inst)
{
    /* Before initialization is done the states follow their start parameters. */
    if (inst->phase < PHASE_STEP && inst->model->n_states > 0)
        inst->model->initial_states(inst->values, inst->x);
    inst->model->outputs(inst->values, inst->time, inst->x);
    inst->outputs_stale = 0;
}

void fmu_handle_events(fmu_instance *inst, double t, double *x)
{
    for (size_t i = 0; i < inst->model->n_event_indicators; ++i)
        if (inst->fired[i])
            fmu_log(inst, fmi2OK, LOG_EVENTS, "internal event %zu at t = %.17g", i, t);
    inst->model->handle_events(inst->values, t, x, inst->fired);
}

void fmu_event_indicators(const fmu_instance *inst, double *z)
{
    if (inst->model->n_event_indicators > 0)
        inst->model->event_indicators(inst->values, inst->time, inst->x, z);
}

fmi2Status fmu_refusal_status(fmu_instance *inst, step_refusal_kind kind)
{
    static const fmi2Status statuses[] = {fmi2Error, fmi2Discard, fmi2Fatal};
    if (statuses[kind] == fmi2Fatal)
        inst->phase = PHASE_FATAL;
    return statuses[kind];
}
