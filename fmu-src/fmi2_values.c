/* fmi2Get and fmi2Set, served from the variable table. */
#include <math.h>
#include <stddef.h>

#include "fmu_instance.h"
#include "fmu_log.h"
#include "fmu_solver.h"


static const char *const type_names[] = {"Real", "Integer", "Boolean"};

static fmi2Status refuse_reference(const fmu_instance *inst, const char *function,
                                   fmi2ValueReference vr)
{
    const model_variable *var = fmu_variable(inst, vr);
    if (var == NULL)
        return fmu_error(inst, "%s: unknown value reference %u", function, vr);
    return fmu_error(inst, "%s: variable %s (value reference %u) is of type %s", function,
                     var->name, vr, type_names[var->type]);
}

/* Checks every value reference before anything is read or written. The model's own variables
 * are looked up directly: this runs on every get and set. */
static fmi2Status check_references(const fmu_instance *inst, const char *function,
                                   const fmi2ValueReference vr[], size_t nvr, variable_type type)
{
    if (nvr > 0 && vr == NULL)
        return fmu_error(inst, "%s: the value reference array is NULL", function);
    const model_variable *model_variables = inst->model->variables;
    const size_t n_model = inst->model->n_variables;
    for (size_t i = 0; i < nvr; ++i) {
        const fmi2ValueReference r = vr[i];
        const model_variable *var = r < n_model ? &model_variables[r] : fmu_variable(inst, r);
        if (var == NULL || var->type != type)
            return refuse_reference(inst, function, r);
    }
    return fmi2OK;
}

static fmu_instance *prepare_get(fmi2Component c, const char *function,
                                 const fmi2ValueReference vr[], size_t nvr, const void *value,
                                 variable_type type)
{
    fmu_instance *inst = fmu_checked(c, function, PHASES_ANY);
    if (inst == NULL)
        return NULL;
    if (check_references(inst, function, vr, nvr, type) != fmi2OK)
        return NULL;
    if (nvr > 0 && value == NULL) {
        fmu_error(inst, "%s: the value array is NULL", function);
        return NULL;
    }
    if (inst->outputs_stale) /* outputs follow the current state and inputs */
        fmu_refresh_outputs(inst);
    if (inst->model->read_refusal != NULL) {
        const char *reason = inst->model->read_refusal(inst->values, inst->time);
        if (reason != NULL) {
            fmu_error(inst, "%s at t = %.17g: %s", function, inst->time, reason);
            return NULL;
        }
    }
    return inst;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[])
{
    fmu_instance *inst = prepare_get(c, "fmi2GetReal", vr, nvr, value, TYPE_REAL);
    if (inst == NULL)
        return fmi2Error;
    for (size_t i = 0; i < nvr; ++i)
        value[i] = inst->values[vr[i]];
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[])
{
    fmu_instance *inst = prepare_get(c, "fmi2GetInteger", vr, nvr, value, TYPE_INTEGER);
    if (inst == NULL)
        return fmi2Error;
    for (size_t i = 0; i < nvr; ++i)
        value[i] = (fmi2Integer)inst->values[vr[i]];
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[])
{
    fmu_instance *inst = prepare_get(c, "fmi2GetBoolean", vr, nvr, value, TYPE_BOOLEAN);
    if (inst == NULL)
        return fmi2Error;
    for (size_t i = 0; i < nvr; ++i)
        value[i] = inst->values[vr[i]] != 0.0 ? fmi2True : fmi2False;
    return fmi2OK;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[])
{
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmi2GetString", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    if (nvr == 0)
        return fmi2OK;
    return fmu_error(inst, "fmi2GetString: unknown value reference %u (no String variables)",
                     vr ? vr[0] : 0u);
}

/* Whether the variable may be written now, per FMI 2.0 (causality, variability, phase).
 * Masters re-apply all parameters after fmi2SetFMUstate (SysSimX does): a fixed parameter set
 * after initialization to the value it already has changes nothing and is accepted; a new value
 * is not. */
static fmi2Status check_settable(const fmu_instance *inst, const char *function,
                                 fmi2ValueReference vr, double value)
{
    const model_variable *var = fmu_variable(inst, vr);
    if (var->causality == CAUSALITY_INPUT)
        return fmi2OK;
    if (var->causality == CAUSALITY_PARAMETER) {
        if ((PHASE_BIT(inst->phase) & PHASES_RUNNING) == 0 ||
            var->variability == VARIABILITY_TUNABLE || inst->values[vr] == value)
            return fmi2OK;
        return fmu_error(inst,
                         "%s: %s is a fixed parameter and cannot be changed in %s "
                         "(set it before fmi2ExitInitializationMode, or use fmi2Reset)",
                         function, var->name, fmu_phase_name(inst->phase));
    }
    return fmu_error(inst, "%s: %s is an output or local variable and cannot be set", function,
                     var->name);
}

static fmu_instance *prepare_set(fmi2Component c, const char *function,
                                 const fmi2ValueReference vr[], size_t nvr, const void *value,
                                 variable_type type)
{
    fmu_instance *inst = fmu_checked(c, function, PHASES_SETTABLE);
    if (inst == NULL)
        return NULL;
    if (check_references(inst, function, vr, nvr, type) != fmi2OK)
        return NULL;
    if (nvr > 0 && value == NULL) {
        fmu_error(inst, "%s: the value array is NULL", function);
        return NULL;
    }
    return inst;
}

static double real_at(const void *values, size_t i) { return ((const fmi2Real *)values)[i]; }
static double integer_at(const void *values, size_t i)
{
    return (double)((const fmi2Integer *)values)[i];
}
static double boolean_at(const void *values, size_t i)
{
    return ((const fmi2Boolean *)values)[i] != fmi2False ? 1.0 : 0.0;
}

/* Checks every value first, so a refused call stores nothing; a changed value in step mode
 * restarts the integration there. */
static fmi2Status store(fmu_instance *inst, const char *function, const fmi2ValueReference vr[],
                        size_t nvr, const void *values, double (*value_at)(const void *, size_t))
{
    for (size_t i = 0; i < nvr; ++i)
        if (check_settable(inst, function, vr[i], value_at(values, i)) != fmi2OK)
            return fmi2Error;
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
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{
    fmu_instance *inst = prepare_set(c, "fmi2SetReal", vr, nvr, value, TYPE_REAL);
    if (inst == NULL)
        return fmi2Error;
    for (size_t i = 0; i < nvr; ++i)
        if (isnan(value[i]))
            return fmu_error(inst, "fmi2SetReal: value for %s is NaN",
                             fmu_variable(inst, vr[i])->name);
    return store(inst, "fmi2SetReal", vr, nvr, value, real_at);
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{
    fmu_instance *inst = prepare_set(c, "fmi2SetInteger", vr, nvr, value, TYPE_INTEGER);
    if (inst == NULL)
        return fmi2Error;
    return store(inst, "fmi2SetInteger", vr, nvr, value, integer_at);
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{
    fmu_instance *inst = prepare_set(c, "fmi2SetBoolean", vr, nvr, value, TYPE_BOOLEAN);
    if (inst == NULL)
        return fmi2Error;
    return store(inst, "fmi2SetBoolean", vr, nvr, value, boolean_at);
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[])
{
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmi2SetString", PHASES_SETTABLE);
    if (inst == NULL)
        return fmi2Error;
    if (nvr == 0)
        return fmi2OK;
    return fmu_error(inst, "fmi2SetString: unknown value reference %u (no String variables)",
                     vr ? vr[0] : 0u);
}
