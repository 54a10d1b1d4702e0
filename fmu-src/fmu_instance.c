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
    if (inst->event_pending == EVENTS_HANDLED_IN_STEP) {
        inst->event_pending = 0;
        return 0;
    }
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
    free(inst->name);
    free(inst); /* the arrays with it */
}

enum { LINE = 64 };

_Static_assert(offsetof(fmu_instance, intermediate_update) + sizeof(void (*)(void)) <= LINE,
               "what every step reads must stay in the instance's first cache line");

static size_t lines(size_t bytes)
{
    return (bytes + LINE - 1) / LINE * LINE;
}

/* The arrays the model's sizes need, one after the other (each one longer than needed: never
 * of size 0), the values and the states first, right after the instance: a step reads them. */
static size_t arrays_bytes(const model_definition *model, size_t n_variables)
{
    size_t n_states = model->n_states;
    size_t n_indicators = model->n_event_indicators;
    size_t doubles = (n_variables + 1)           /* values */
                     + 2 * (n_states + 1)        /* x, dx */
                     + 3 * (n_indicators + 1)    /* z_before, z_after, z_previous */
                     + (2 * n_variables + 1)     /* input_derivatives */
                     + 2 * (n_variables + 1)     /* input_base, values_scratch */
                     + (2 * n_states + 1);       /* x_scratch */
    return doubles * sizeof(double) + 2 * (n_indicators + 1) * sizeof(int); /* fired, last */
}

static void place_arrays(fmu_instance *inst, double *at)
{
    size_t n_states = inst->model->n_states;
    size_t n_indicators = inst->model->n_event_indicators;
    inst->values = at;
    at += inst->n_variables + 1;
    inst->x = at;
    at += n_states + 1;
    inst->dx = at;
    at += n_states + 1;
    inst->z_before = at;
    at += n_indicators + 1;
    inst->z_after = at;
    at += n_indicators + 1;
    inst->z_previous = at;
    at += n_indicators + 1;
    inst->input_derivatives = at;
    at += 2 * inst->n_variables + 1;
    inst->input_base = at;
    at += inst->n_variables + 1;
    inst->values_scratch = at;
    at += inst->n_variables + 1;
    inst->x_scratch = at;
    at += 2 * n_states + 1;
    inst->fired = (int *)at;
    inst->fired_in_step = inst->fired + n_indicators + 1;
}

/* The instance (`size` bytes) and its arrays in one zeroed block aligned to a cache line. */
static fmu_instance *allocate_instance(size_t size)
{
    size_t n_variables = fmu_model.n_variables + fmu_solver_variable_count;
    size_t head = lines(size);
    size_t bytes = lines(head + arrays_bytes(&fmu_model, n_variables));
    fmu_instance *inst = aligned_alloc(LINE, bytes);
    if (inst == NULL)
        return NULL;
    memset(inst, 0, bytes);
    inst->model = &fmu_model;
    inst->n_variables = n_variables;
    place_arrays(inst, (double *)((char *)inst + head));
    return inst;
}

fmu_instance *fmu_instance_create(const fmu_instance *reporter, size_t size, const char *function)
{
    fmu_instance *inst = allocate_instance(size);
    if (inst == NULL) {
        fmu_error(reporter, "%s: out of memory", function);
        return NULL;
    }
    inst->callbacks = reporter->callbacks;
    inst->logging_on = reporter->logging_on;
    inst->log_categories = LOG_ALL_CATEGORIES;
    inst->solver_variables = fmu_solver_variables;
    inst->phase = PHASE_INSTANTIATED;
    inst->running_phase = PHASE_STEP;
    inst->name = malloc(strlen(reporter->name) + 1);
    if (inst->name == NULL) {
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
