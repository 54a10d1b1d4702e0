#include "fmu_interpolation.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "fmu_evaluation.h"
#include "fmu_log.h"
#include "fmu_solver.h"

static int is_real_input(const model_variable *v)
{
    return v != NULL && v->type == TYPE_REAL && v->causality == CAUSALITY_INPUT;
}

fmu_status fmu_set_input_derivatives(fmu_instance *inst, const char *function,
                                     const unsigned int vr[], size_t nvr,
                                     const int order[], const double value[])
{
    if (nvr > 0 && (vr == NULL || order == NULL || value == NULL))
        return fmu_error(inst, "%s: an argument array is NULL", function);
    for (size_t i = 0; i < nvr; ++i) {
        const model_variable *v = fmu_variable(inst, vr[i]);
        if (!is_real_input(v))
            return fmu_error(inst, "%s: value reference %u is not a Real input", function,
                             vr[i]);
        if (order[i] < 1 || order[i] > FMU_MAX_INPUT_DERIVATIVE_ORDER)
            return fmu_error(inst, "%s: derivative order %d of %s is not in 1..%d", function,
                             order[i], v->name, FMU_MAX_INPUT_DERIVATIVE_ORDER);
        if (!isfinite(value[i]))
            return fmu_error(inst, "%s: derivative %d of %s is not finite", function, order[i],
                             v->name);
    }
    int changed = 0;
    for (size_t i = 0; i < nvr; ++i) {
        double *slot = &inst->input_derivatives[2 * vr[i] + (size_t)(order[i] - 1)];
        changed |= *slot != value[i];
        *slot = value[i];
    }
    inst->has_input_derivatives = 0;
    for (size_t k = 0; k < 2 * inst->n_variables; ++k)
        inst->has_input_derivatives |= inst->input_derivatives[k] != 0.0;
    if (changed) {
        inst->outputs_stale = 1;
        fmu_solver_invalidate(inst); /* the right-hand side changed */
    }
    return FMU_OK;
}

void fmu_inputs_begin_step(fmu_instance *inst)
{
    /* held inputs (most steps) write nothing here: the instance's second line stays unread */
    if (inst->intermediate_update != NULL) {
        inst->input_motion = INPUTS_INTERMEDIATE_UPDATE;
    } else if (inst->has_input_derivatives) {
        inst->step_start = inst->time;
        memcpy(inst->input_base, inst->values, inst->n_variables * sizeof(double));
        inst->input_motion = INPUTS_POLYNOMIAL;
    }
}

void fmu_inputs_end_step(fmu_instance *inst, double t_end)
{
    if (inst->input_motion == INPUTS_HELD)
        return;
    fmu_inputs_follow(inst, t_end);
    if (inst->input_motion == INPUTS_POLYNOMIAL) {
        /* the polynomial goes on from t_end: its slope there */
        double tau = t_end - inst->step_start;
        for (size_t vr = 0; vr < inst->n_variables; ++vr)
            inst->input_derivatives[2 * vr] += tau * inst->input_derivatives[2 * vr + 1];
    }
    inst->input_motion = INPUTS_HELD;
}

/* The outputs at t + eps along the trajectory through the current point, into values_scratch:
 * the states moved by eps times their derivatives (x_scratch + n), the inputs by their
 * polynomial. */
static void outputs_along(fmu_instance *inst, double eps)
{
    size_t n = inst->model->n_states;
    double *v = inst->values_scratch;
    memcpy(v, inst->values, inst->n_variables * sizeof(double));
    for (size_t vr = 0; vr < inst->n_variables; ++vr) {
        const double *d = &inst->input_derivatives[2 * vr];
        v[vr] += eps * (d[0] + 0.5 * eps * d[1]);
    }
    double *x = inst->x_scratch;
    for (size_t i = 0; i < n; ++i)
        x[i] = inst->x[i] + eps * x[n + i];
    inst->model->outputs(v, inst->time + eps, x);
}

fmu_status fmu_get_output_derivatives(fmu_instance *inst, const char *function,
                                      const unsigned int vr[], size_t nvr,
                                      const int order[], double value[])
{
    if (nvr > 0 && (vr == NULL || order == NULL || value == NULL))
        return fmu_error(inst, "%s: an argument array is NULL", function);
    for (size_t i = 0; i < nvr; ++i) {
        const model_variable *v = fmu_variable(inst, vr[i]);
        if (v == NULL || v->type != TYPE_REAL || v->causality != CAUSALITY_OUTPUT)
            return fmu_error(inst, "%s: value reference %u is not a Real output", function,
                             vr[i]);
        if (order[i] < 1 || order[i] > FMU_MAX_OUTPUT_DERIVATIVE_ORDER)
            return fmu_error(inst, "%s: derivative order %d of %s is not in 1..%d", function,
                             order[i], v->name, FMU_MAX_OUTPUT_DERIVATIVE_ORDER);
    }
    if (inst->outputs_stale)
        fmu_refresh_outputs(inst);
    size_t n = inst->model->n_states;
    if (n > 0)
        inst->model->derivatives(inst->values, inst->time, inst->x, inst->x_scratch + n);
    /* central difference: its truncation error (eps^2) and rounding error (DBL_EPSILON / eps)
     * balance near the cube root of DBL_EPSILON, relative to the time scale */
    double eps = cbrt(DBL_EPSILON) * fmax(1.0, fabs(inst->time));
    outputs_along(inst, eps);
    for (size_t i = 0; i < nvr; ++i)
        value[i] = inst->values_scratch[vr[i]];
    outputs_along(inst, -eps);
    for (size_t i = 0; i < nvr; ++i) {
        const model_variable *v = fmu_variable(inst, vr[i]);
        value[i] = v->variability == VARIABILITY_CONTINUOUS
                       ? (value[i] - inst->values_scratch[vr[i]]) / (2.0 * eps)
                       : 0.0;
    }
    return FMU_OK;
}
