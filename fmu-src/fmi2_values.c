/* fmi2Get and fmi2Set, served from the variable table. */
#include <stddef.h>

#include "fmi2_allowed.h"
#include "fmu_instance.h"
#include "fmu_log.h"
#include "fmu_values.h"

static fmu_instance *prepare_get(fmi2Component c, const char *function, unsigned allowed,
                                 const fmi2ValueReference vr[], size_t nvr, const void *value,
                                 variable_type type)
{
    fmu_instance *inst = fmu_checked(c, function, allowed);
    if (inst == NULL || fmu_check_references(inst, function, vr, nvr, value, type) != FMU_OK ||
        fmu_prepare_read(inst, function) != FMU_OK)
        return NULL;
    return inst;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[])
{
    fmu_instance *inst = prepare_get(c, FMI2_CALL(fmi2GetReal), vr, nvr, value, TYPE_REAL);
    if (inst == NULL)
        return fmi2Error;
    for (size_t i = 0; i < nvr; ++i)
        value[i] = inst->values[vr[i]];
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[])
{
    fmu_instance *inst = prepare_get(c, FMI2_CALL(fmi2GetInteger), vr, nvr, value, TYPE_INTEGER);
    if (inst == NULL)
        return fmi2Error;
    for (size_t i = 0; i < nvr; ++i)
        value[i] = (fmi2Integer)inst->values[vr[i]];
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[])
{
    fmu_instance *inst = prepare_get(c, FMI2_CALL(fmi2GetBoolean), vr, nvr, value, TYPE_BOOLEAN);
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
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetString));
    if (inst == NULL)
        return fmi2Error;
    if (nvr == 0)
        return fmi2OK;
    return fmi2_status(fmu_error(inst,
                                 "fmi2GetString: unknown value reference %u (no String variables)",
                                 vr ? vr[0] : 0u));
}

static fmu_instance *prepare_set(fmi2Component c, const char *function, unsigned allowed,
                                 const fmi2ValueReference vr[], size_t nvr, const void *value,
                                 variable_type type)
{
    fmu_instance *inst = fmu_checked(c, function, allowed);
    if (inst == NULL || fmu_check_references(inst, function, vr, nvr, value, type) != FMU_OK)
        return NULL;
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

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{
    fmu_instance *inst = prepare_set(c, FMI2_CALL(fmi2SetReal), vr, nvr, value, TYPE_REAL);
    if (inst == NULL || fmu_check_reals(inst, "fmi2SetReal", vr, nvr, value) != FMU_OK)
        return fmi2Error;
    return fmi2_status(fmu_store(inst, "fmi2SetReal", vr, nvr, value, real_at));
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{
    fmu_instance *inst = prepare_set(c, FMI2_CALL(fmi2SetInteger), vr, nvr, value, TYPE_INTEGER);
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_store(inst, "fmi2SetInteger", vr, nvr, value, integer_at));
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{
    fmu_instance *inst = prepare_set(c, FMI2_CALL(fmi2SetBoolean), vr, nvr, value, TYPE_BOOLEAN);
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_store(inst, "fmi2SetBoolean", vr, nvr, value, boolean_at));
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[])
{
    (void)value;
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2SetString));
    if (inst == NULL)
        return fmi2Error;
    if (nvr == 0)
        return fmi2OK;
    return fmi2_status(fmu_error(inst,
                                 "fmi2SetString: unknown value reference %u (no String variables)",
                                 vr ? vr[0] : 0u));
}
