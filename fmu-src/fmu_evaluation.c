/* The model's equations applied to an instance (see fmu_evaluation.h). */
#include "fmu_evaluation.h"

#include "fmu_log.h"

double fmu_solver_parameter(const fmu_instance *inst, size_t i)
{
    return inst->values[inst->model->n_variables + i];
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
    for (size_t i = 0; i < inst->model->n_event_indicators; ++i) {
        if (inst->fired[i])
            fmu_log(inst, FMU_OK, LOG_EVENTS, "internal event %zu at t = %.17g", i, t);
        inst->fired_in_step[i] |= inst->fired[i];
    }
    inst->model->handle_events(inst->values, t, x, inst->fired);
}

void fmu_event_indicators(const fmu_instance *inst, double *z)
{
    if (inst->model->n_event_indicators > 0)
        inst->model->event_indicators(inst->values, inst->time, inst->x, z);
}

void fmu_inputs_follow(fmu_instance *inst, double t)
{
    if (inst->input_motion == INPUTS_INTERMEDIATE_UPDATE) {
        inst->intermediate_update(inst, t);
        return;
    }
    double tau = t - inst->step_start;
    for (size_t vr = 0; vr < inst->n_variables; ++vr) {
        const double *d = &inst->input_derivatives[2 * vr];
        if (d[0] != 0.0 || d[1] != 0.0)
            inst->values[vr] = inst->input_base[vr] + tau * (d[0] + 0.5 * tau * d[1]);
    }
}
