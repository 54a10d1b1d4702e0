/* Fixed-step explicit Euler. The communication interval is covered exactly: full substeps of
 * euler_step_size, the last one shortened. An internal event is located inside the substep
 * where an indicator crosses by linear interpolation of the indicator; the Euler step to that
 * point is then taken, the event applied, and stepping resumes from there (or, when the
 * importer handles events, the step ends there with the event pending). */
#include <math.h>
#include <stdlib.h>

#include "fmu_evaluation.h"
#include "fmu_log.h"
#include "fmu_solver.h"

enum { EULER_STEP_SIZE };

const model_variable fmu_solver_variables[] = {
    REAL_PARAMETER(EULER_STEP_SIZE, "euler_step_size", "s", 1e-4,
                   "step size of the explicit Euler integrator"),
};
const size_t fmu_solver_variable_count = sizeof fmu_solver_variables / sizeof *fmu_solver_variables;
const char fmu_solver_name[] = "euler";

/* More internal events than this in one communication step is chattering. */
#define MAX_EVENTS_PER_STEP 10000

typedef struct {
    double *x_next;
} euler_data;

int fmu_solver_create(fmu_instance *inst)
{
    euler_data *data = calloc(1, sizeof *data);
    if (data == NULL)
        return -1;
    data->x_next = calloc(inst->model->n_states + 1, sizeof(double));
    if (data->x_next == NULL) {
        free(data);
        return -1;
    }
    inst->solver = data;
    return 0;
}

void fmu_solver_free(fmu_instance *inst)
{
    euler_data *data = inst->solver;
    if (data != NULL)
        free(data->x_next);
    free(data);
    inst->solver = NULL;
}

void fmu_solver_invalidate(fmu_instance *inst)
{
    (void)inst; /* Euler is one-step: it keeps no history to restart */
}

/* Fraction of the substep at which the earliest indicator crosses, or 2 when none does.
 * Marks the indicators that cross at that fraction in inst->fired. */
static double earliest_crossing(fmu_instance *inst)
{
    size_t n = inst->model->n_event_indicators;
    double earliest = 2.0;
    for (size_t i = 0; i < n; ++i) {
        double before = inst->z_before[i], after = inst->z_after[i];
        if (before > 0.0 && after <= 0.0) {
            double fraction = before / (before - after);
            if (fraction < earliest)
                earliest = fraction;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        double before = inst->z_before[i], after = inst->z_after[i];
        inst->fired[i] = before > 0.0 && after <= 0.0 &&
                         before / (before - after) <= earliest * (1.0 + 1e-12);
    }
    return earliest;
}

fmu_status fmu_solver_step(fmu_instance *inst, double t_end)
{
    const model_definition *model = inst->model;
    euler_data *data = inst->solver;
    size_t n = model->n_states;
    double h = fmu_solver_parameter(inst, EULER_STEP_SIZE);
    if (!(h > 0.0) || !isfinite(h))
        return fmu_error(inst, "euler_step_size must be positive, it is %g", h);
    double segment_start = inst->time; /* substeps are counted from here to avoid drift */
    long substeps = 0;
    int events = 0;
    double t = inst->time;
    while (t < t_end) {
        double t_next = segment_start + (double)(substeps + 1) * h;
        /* the last substep ends exactly at t_end; a sliver below 1e-9 h joins it */
        if (t_next >= t_end - 1e-9 * h)
            t_next = t_end;
        double step = t_next - t;
        fmu_inputs_at(inst, t);
        model->derivatives(inst->values, t, inst->x, inst->dx);
        for (size_t i = 0; i < n; ++i)
            data->x_next[i] = inst->x[i] + step * inst->dx[i];
        double fraction = 2.0;
        if (model->n_event_indicators > 0) {
            model->event_indicators(inst->values, t, inst->x, inst->z_before);
            fmu_inputs_at(inst, t_next);
            model->event_indicators(inst->values, t_next, data->x_next, inst->z_after);
            fraction = earliest_crossing(inst);
        }
        if (fraction > 1.0) {
            for (size_t i = 0; i < n; ++i)
                inst->x[i] = data->x_next[i];
            t = t_next;
            ++substeps;
            continue;
        }
        double t_event = fraction >= 1.0 ? t_next : t + fraction * step;
        double partial = t_event - t;
        for (size_t i = 0; i < n; ++i)
            inst->x[i] += partial * inst->dx[i];
        t = t_event;
        if (inst->importer_handles_events) {
            /* stop at the located point; the importer applies the event in event mode */
            inst->time = t;
            inst->event_pending = 1;
            return FMU_OK;
        }
        fmu_handle_events(inst, t, inst->x);
        if (++events > MAX_EVENTS_PER_STEP) {
            inst->time = t;
            return fmu_error(inst, "more than %d internal events in one step at t = %.17g: "
                                   "the model chatters",
                             MAX_EVENTS_PER_STEP, t);
        }
        segment_start = t;
        substeps = 0;
    }
    inst->time = t_end;
    return FMU_OK;
}
