/* Directional derivatives from the model's partial derivatives of outputs with respect to
 * inputs: dv_unknown_i = sum_j d unknown_i / d known_j * dv_known_j, states held fixed. */
#include "fmu_derivatives.h"

#include "fmu_log.h"

static fmu_status check_role(const fmu_instance *inst, const char *function,
                             unsigned int vr, variable_causality causality,
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
    return FMU_OK;
}

fmu_status fmu_directional_derivative(fmu_instance *inst, const char *function,
                                      const unsigned int vUnknown_ref[], size_t nUnknown,
                                      const unsigned int vKnown_ref[], size_t nKnown,
                                      const double dvKnown[], double dvUnknown[])
{
    const model_definition *model = inst->model;
    if (model->partial_derivative == NULL)
        return fmu_error(inst, "%s is not provided by model %s", function, model->name);
    if ((nUnknown > 0 && (vUnknown_ref == NULL || dvUnknown == NULL)) ||
        (nKnown > 0 && (vKnown_ref == NULL || dvKnown == NULL)))
        return fmu_error(inst, "%s: an array argument is NULL", function);
    for (size_t i = 0; i < nUnknown; ++i) {
        if (check_role(inst, function, vUnknown_ref[i], CAUSALITY_OUTPUT, "output") != FMU_OK)
            return FMU_ERROR;
    }
    for (size_t j = 0; j < nKnown; ++j) {
        if (check_role(inst, function, vKnown_ref[j], CAUSALITY_INPUT, "input") != FMU_OK)
            return FMU_ERROR;
    }
    for (size_t i = 0; i < nUnknown; ++i) {
        double sum = 0.0;
        for (size_t j = 0; j < nKnown; ++j)
            sum += model->partial_derivative(inst->values, inst->x, vUnknown_ref[i],
                                             vKnown_ref[j]) *
                   dvKnown[j];
        dvUnknown[i] = sum;
    }
    return FMU_OK;
}
