/* Directional derivatives from the model's partial derivatives of outputs with respect to
 * inputs: dv_unknown_i = sum_j d unknown_i / d known_j * dv_known_j, states held fixed. */
#include "fmu_derivatives.h"

#include "fmu_log.h"

static fmi2Status check_role(const fmu_instance *inst, const char *function,
                             fmi2ValueReference vr, variable_causality causality,
                             const char *role)
{
    const model_variable *var = fmu_variable(inst, vr);
    if (var == NULL)
        return fmu_error(inst, "%s: unknown value reference %u", function, vr);
    if (var->causality != causality || var->type != TYPE_REAL)
        return fmu_error(inst,
                         "%s: variable %s (value reference %u) is not a Real %s; only "
                         "derivatives of outputs with respect to inputs are provided",
                         function, var->name, vr, role);
    return fmi2OK;
}

fmi2Status fmu_directional_derivative(fmu_instance *inst, const char *function,
                                      const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                      const fmi2ValueReference vKnown_ref[], size_t nKnown,
                                      const double dvKnown[], double dvUnknown[])
{
    const model_definition *model = inst->model;
    if (model->partial_derivative == NULL)
        return fmu_error(inst, "%s is not provided by model %s", function, model->name);
    if ((nUnknown > 0 && (vUnknown_ref == NULL || dvUnknown == NULL)) ||
        (nKnown > 0 && (vKnown_ref == NULL || dvKnown == NULL)))
        return fmu_error(inst, "%s: an array argument is NULL", function);
    for (size_t i = 0; i < nUnknown; ++i) {
        if (check_role(inst, function, vUnknown_ref[i], CAUSALITY_OUTPUT, "output") != fmi2OK)
            return fmi2Error;
    }
    for (size_t j = 0; j < nKnown; ++j) {
        if (check_role(inst, function, vKnown_ref[j], CAUSALITY_INPUT, "input") != fmi2OK)
            return fmi2Error;
    }
    for (size_t i = 0; i < nUnknown; ++i) {
        double sum = 0.0;
        for (size_t j = 0; j < nKnown; ++j)
            sum += model->partial_derivative(inst->values, inst->x, vUnknown_ref[i],
                                             vKnown_ref[j]) *
                   dvKnown[j];
        dvUnknown[i] = sum;
    }
    return fmi2OK;
}
