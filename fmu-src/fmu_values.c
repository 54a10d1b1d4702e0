/* Variable access shared by every interface: value reference checks, reads, checked stores. */
#include "fmu_values.h"

#include <math.h>
#include <stddef.h>

#include "fmu_evaluation.h"
#include "fmu_log.h"
#include "fmu_solver.h"

const char *const fmu_type_names[] = {"Real", "Integer", "Boolean"};

fmu_status fmu_refuse_reference(const fmu_instance *inst, const char *function,
                                unsigned int vr)
{
    const model_variable *var = fmu_variable(inst, vr);
    if (var == NULL)
        return fmu_error(inst, "%s: unknown value reference %u", function, vr);
    return fmu_error(inst, "%s: variable %s (value reference %u) is of type %s", function,
                     var->name, vr, fmu_type_names[var->type]);
}

/* The model's own variables are looked up directly: this runs on every get and set. */
fmu_status fmu_check_references(const fmu_instance *inst, const char *function,
                                const unsigned int vr[], size_t nvr, const void *value,
                                variable_type type)
{
    if (nvr > 0 && vr == NULL)
        return fmu_error(inst, "%s: the value reference array is NULL", function);
    if (nvr > 0 && value == NULL)
        return fmu_error(inst, "%s: the value array is NULL", function);
    const model_variable *model_variables = inst->model->variables;
    const size_t n_model = inst->model->n_variables;
    for (size_t i = 0; i < nvr; ++i) {
        const unsigned int r = vr[i];
        const model_variable *var = r < n_model ? &model_variables[r] : fmu_variable(inst, r);
        if (var == NULL || var->type != type)
            return fmu_refuse_reference(inst, function, r);
    }
    return FMU_OK;
}

fmu_status fmu_prepare_read(fmu_instance *inst, const char *function)
{
    if (inst->outputs_stale) /* outputs follow the current state and inputs */
        fmu_refresh_outputs(inst);
    if (inst->model->read_refusal != NULL) {
        const char *reason = inst->model->read_refusal(inst->values, inst->time);
        if (reason != NULL)
            return fmu_error(inst, "%s at t = %.17g: %s", function, inst->time, reason);
    }
    return FMU_OK;
}

/* Whether the variable may be written now (causality, variability, phase). Masters re-apply
 * all parameters after a state restore (SysSimX does): a fixed parameter set after
 * initialization to the value it already has changes nothing and is accepted; a new value is
 * not. */
static fmu_status check_settable(const fmu_instance *inst, const char *function,
                                 unsigned int vr, double value)
{
    const model_variable *var = fmu_variable(inst, vr);
    if (var->causality == CAUSALITY_INPUT)
        return FMU_OK;
    if (var->causality == CAUSALITY_PARAMETER) {
        if ((PHASE_BIT(inst->phase) & PHASES_RUNNING) == 0 ||
            var->variability == VARIABILITY_TUNABLE || inst->values[vr] == value)
            return FMU_OK;
        /* the hint names the calls of the caller's interface: fmi2... or fmi3... */
        return fmu_error(inst,
                         "%s: %s is a fixed parameter and cannot be changed in %s "
                         "(set it before %.4sExitInitializationMode, or use %.4sReset)",
                         function, var->name, fmu_phase_name(inst->phase), function, function);
    }
    return fmu_error(inst, "%s: %s is an output or local variable and cannot be set", function,
                     var->name);
}

fmu_status fmu_store(fmu_instance *inst, const char *function, const unsigned int vr[],
                     size_t nvr, const void *values, double (*value_at)(const void *, size_t))
{
    for (size_t i = 0; i < nvr; ++i)
        if (check_settable(inst, function, vr[i], value_at(values, i)) != FMU_OK)
            return FMU_ERROR;
    int changed = 0;
    for (size_t i = 0; i < nvr; ++i) {
        double value = value_at(values, i);
        changed |= inst->values[vr[i]] != value;
        inst->values[vr[i]] = value;
    }
    if (changed) {
        inst->outputs_stale = 1;
        if (inst->phase == PHASE_STEP)
            fmu_solver_invalidate(inst);
    }
    return FMU_OK;
}

fmu_status fmu_check_reals(const fmu_instance *inst, const char *function,
                           const unsigned int vr[], size_t nvr, const double values[])
{
    for (size_t i = 0; i < nvr; ++i)
        if (isnan(values[i]))
            return fmu_error(inst, "%s: value for %s is NaN", function,
                             fmu_variable(inst, vr[i])->name);
    return FMU_OK;
}
