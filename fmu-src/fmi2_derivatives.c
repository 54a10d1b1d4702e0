/* fmi2GetDirectionalDerivative from the model's partial derivatives of outputs with respect to
 * inputs: dv_unknown_i = sum_j d unknown_i / d known_j * dv_known_j, states held fixed. */
#include "fmu_instance.h"
#include "fmu_log.h"

#define FUNCTION "fmi2GetDirectionalDerivative"

static fmi2Status check_role(const fmu_instance *inst, fmi2ValueReference vr,
                             variable_causality causality, const char *role)
{
    const model_variable *var = fmu_variable(inst, vr);
    if (var == NULL)
        return fmu_error(inst, FUNCTION ": unknown value reference %u", vr);
    if (var->causality != causality || var->type != TYPE_REAL)
        return fmu_error(inst,
                         FUNCTION ": variable %s (value reference %u) is not a Real %s; only "
                         "derivatives of outputs with respect to inputs are provided",
                         var->name, vr, role);
    return fmi2OK;
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    fmu_instance *inst = fmu_checked(c, FUNCTION, PHASES_INITIALIZED);
    if (inst == NULL)
        return fmi2Error;
    const model_definition *model = inst->model;
    if (model->partial_derivative == NULL)
        return fmu_error(inst, FUNCTION " is not provided by model %s", model->name);
    if ((nUnknown > 0 && (vUnknown_ref == NULL || dvUnknown == NULL)) ||
        (nKnown > 0 && (vKnown_ref == NULL || dvKnown == NULL)))
        return fmu_error(inst, FUNCTION ": an array argument is NULL");
    for (size_t i = 0; i < nUnknown; ++i) {
        if (check_role(inst, vUnknown_ref[i], CAUSALITY_OUTPUT, "output") != fmi2OK)
            return fmi2Error;
    }
    for (size_t j = 0; j < nKnown; ++j) {
        if (check_role(inst, vKnown_ref[j], CAUSALITY_INPUT, "input") != fmi2OK)
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
