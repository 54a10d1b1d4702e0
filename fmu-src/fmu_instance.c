#include "fmu_instance.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_evaluation.h"
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

void fmu_apply_start_values(fmu_instance *inst)
{
    for (size_t vr = 0; vr < inst->n_variables; ++vr)
        inst->values[vr] = fmu_variable(inst, (unsigned int)vr)->start;
    inst->time = 0.0;
    inst->tolerance_defined = 0;
    inst->tolerance = 0.0;
    if (inst->model->n_states > 0)
        inst->model->initial_states(inst->values, inst->x);
    fmu_refresh_outputs(inst);
}

fmu_status fmu_refusal_status(fmu_instance *inst, step_refusal_kind kind)
{
    static const fmu_status statuses[] = {FMU_ERROR, FMU_DISCARD, FMU_FATAL};
    if (statuses[kind] == FMU_FATAL)
        inst->phase = PHASE_FATAL;
    return statuses[kind];
}

int fmu_apply_pending_events(fmu_instance *inst)
{
    if (!inst->event_pending)
        return 0;
    size_t n = inst->model->n_states;
    /* dx is scratch between steps: keep the states from before the event to compare */
    for (size_t i = 0; i < n; ++i)
        inst->dx[i] = inst->x[i];
    fmu_handle_events(inst, inst->time, inst->x);
    inst->event_pending = 0;
    inst->outputs_stale = 1;
    fmu_solver_invalidate(inst);
    int changed = 0;
    for (size_t i = 0; i < n; ++i)
        changed |= inst->dx[i] != inst->x[i];
    return changed;
}

void fmu_instance_free(fmu_instance *inst)
{
    if (inst == NULL)
        return;
    fmu_solver_free(inst);
    free(inst->values);
    free(inst->x);
    free(inst->dx);
    free(inst->z_before);
    free(inst->z_after);
    free(inst->fired);
    free(inst->z_previous);
    free(inst->input_derivatives);
    free(inst->input_base);
    free(inst->values_scratch);
    free(inst->x_scratch);
    free(inst->name);
    free(inst);
}

static int allocate_arrays(fmu_instance *inst)
{
    size_t n_states = inst->model->n_states;
    size_t n_indicators = inst->model->n_event_indicators;
    /* calloc(0) may return NULL: allocate at least one element so NULL always means failure */
    inst->values = calloc(inst->n_variables + 1, sizeof(double));
    inst->x = calloc(n_states + 1, sizeof(double));
    inst->dx = calloc(n_states + 1, sizeof(double));
    inst->z_before = calloc(n_indicators + 1, sizeof(double));
    inst->z_after = calloc(n_indicators + 1, sizeof(double));
    inst->fired = calloc(n_indicators + 1, sizeof(int));
    inst->z_previous = calloc(n_indicators + 1, sizeof(double));
    inst->input_derivatives = calloc(2 * inst->n_variables + 1, sizeof(double));
    inst->input_base = calloc(inst->n_variables + 1, sizeof(double));
    inst->values_scratch = calloc(inst->n_variables + 1, sizeof(double));
    inst->x_scratch = calloc(2 * n_states + 1, sizeof(double));
    return inst->values && inst->x && inst->dx && inst->z_before && inst->z_after && inst->fired &&
           inst->z_previous && inst->input_derivatives && inst->input_base &&
           inst->values_scratch && inst->x_scratch;
}

fmu_instance *fmu_instance_create(const fmu_instance *reporter, size_t size, const char *function)
{
    fmu_instance *inst = calloc(1, size);
    if (inst == NULL) {
        fmu_error(reporter, "%s: out of memory", function);
        return NULL;
    }
    inst->callbacks = reporter->callbacks;
    inst->logging_on = reporter->logging_on;
    inst->log_categories = LOG_ALL_CATEGORIES;
    inst->model = &fmu_model;
    inst->solver_variables = fmu_solver_variables;
    inst->n_variables = fmu_model.n_variables + fmu_solver_variable_count;
    inst->phase = PHASE_INSTANTIATED;
    inst->running_phase = PHASE_STEP;
    inst->name = malloc(strlen(reporter->name) + 1);
    if (inst->name == NULL || !allocate_arrays(inst)) {
        fmu_error(reporter, "%s: out of memory", function);
        fmu_instance_free(inst);
        return NULL;
    }
    strcpy(inst->name, reporter->name);
    fmu_guid(inst->guid);
    fmu_apply_start_values(inst);
    if (fmu_solver_create(inst) != 0) {
        fmu_error(reporter, "%s: the %s solver could not be created", function, fmu_solver_name);
        fmu_instance_free(inst);
        return NULL;
    }
    return inst;
}

fmu_status fmu_setup_experiment(fmu_instance *inst, const char *function, int tolerance_defined,
                                double tolerance, double start_time, int stop_time_defined,
                                double stop_time)
{
    if (!isfinite(start_time))
        return fmu_error(inst, "%s: the start time is not finite", function);
    if (tolerance_defined && !(tolerance > 0.0 && tolerance < 1.0))
        return fmu_error(inst, "%s: tolerance %g is not in (0, 1)", function, tolerance);
    if (stop_time_defined && !(stop_time >= start_time))
        return fmu_error(inst, "%s: stop time %g is before start time %g", function, stop_time,
                         start_time);
    inst->tolerance_defined = tolerance_defined;
    inst->tolerance = tolerance_defined ? tolerance : 0.0;
    inst->time = start_time;
    inst->outputs_stale = 1;
    return FMU_OK;
}

void fmu_exit_initialization(fmu_instance *inst)
{
    fmu_refresh_outputs(inst); /* states from the final start values */
    inst->phase = inst->running_phase;
    fmu_refresh_outputs(inst);
    fmu_solver_invalidate(inst);
    /* Model Exchange: the first event mode compares the indicators with their initial values */
    fmu_event_indicators(inst, inst->z_previous);
}

void fmu_hold_inputs(fmu_instance *inst)
{
    memset(inst->input_derivatives, 0, 2 * inst->n_variables * sizeof(double));
    inst->has_input_derivatives = 0;
    inst->input_motion = INPUTS_HELD;
}

void fmu_reset(fmu_instance *inst)
{
    inst->phase = PHASE_INSTANTIATED;
    inst->event_pending = 0;
    inst->in_event_mode = 0;
    fmu_hold_inputs(inst);
    fmu_apply_start_values(inst);
    fmu_solver_invalidate(inst);
}
