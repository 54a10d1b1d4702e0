/* FMI 3.0 get and set: Float64, Int32 and Boolean from the variable table, plus time and the
 * event indicators; the other types have no variables in these FMUs. */
#include <stdbool.h>
#include <stdint.h>

#include "fmi3_allowed.h"
#include "fmi3_instance.h"
#include "fmu_log.h"
#include "fmu_values.h"

static const char *const type_names[] = {"Float64", "Int32", "Boolean"};

/* Which FMI 3.0 extra a value reference is: 0 none, 1 time, 2 an event indicator. */
static int extra_kind(const fmu_instance *inst, fmi3ValueReference vr)
{
    fmi3ValueReference first_indicator = fmi3_indicator_vr(inst->n_variables, 0);
    if (vr == fmi3_time_vr(inst->n_variables))
        return 1;
    if (vr >= first_indicator && vr - first_indicator < inst->model->n_event_indicators)
        return 2;
    return 0;
}

static const char *extra_name(int kind)
{
    return kind == 1 ? "time" : "an event indicator";
}

/* Checks the arrays and every value reference: known, of `type`, and settable extras refused. */
static fmi3_instance *checked(fmi3Instance instance, const char *function, unsigned allowed,
                              const fmi3ValueReference vr[], size_t nvr, const void *values,
                              size_t nValues, variable_type type, int for_set)
{
    fmi3_instance *self = fmi3_checked(instance, function, allowed);
    if (self == NULL)
        return NULL;
    fmu_instance *inst = &self->core;
    if (nvr > 0 && (vr == NULL || values == NULL)) {
        fmu_error(inst, "%s: an array argument is NULL", function);
        return NULL;
    }
    if (nValues != nvr) {
        fmu_error(inst, "%s: %zu values for %zu value references (the variables are scalars)",
                  function, nValues, nvr);
        return NULL;
    }
    for (size_t i = 0; i < nvr; ++i) {
        int extra = extra_kind(inst, vr[i]);
        const model_variable *var = extra ? NULL : fmu_variable(inst, vr[i]);
        const char *actual = extra ? "Float64" : var ? type_names[var->type] : NULL;
        if (actual == NULL)
            fmu_error(inst, "%s: unknown value reference %u", function, vr[i]);
        else if ((extra ? TYPE_REAL : var->type) != type)
            fmu_error(inst, "%s: variable %s (value reference %u) is of type %s", function,
                      extra ? extra_name(extra) : var->name, vr[i], actual);
        else if (extra && for_set)
            fmu_error(inst, "%s: %s (value reference %u) is computed by the FMU and cannot be "
                            "set",
                      function, extra_name(extra), vr[i]);
        else
            continue;
        return NULL;
    }
    if (!for_set && fmu_prepare_read(inst, function) != FMU_OK)
        return NULL;
    return self;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float64 values[], size_t nValues)
{
    fmi3_instance *self = checked(instance, FMI3_CALL(fmi3GetFloat64), valueReferences,
                                  nValueReferences, values, nValues, TYPE_REAL, 0);
    if (self == NULL)
        return fmi3Error;
    fmu_instance *inst = &self->core;
    int indicators_known = 0;
    for (size_t i = 0; i < nValueReferences; ++i) {
        fmi3ValueReference vr = valueReferences[i];
        switch (extra_kind(inst, vr)) {
        case 0: values[i] = inst->values[vr]; break;
        case 1: values[i] = inst->time; break;
        default:
            if (!indicators_known) { /* z_after is scratch between steps */
                inst->model->event_indicators(inst->values, inst->time, inst->x, inst->z_after);
                indicators_known = 1;
            }
            values[i] = inst->z_after[vr - fmi3_indicator_vr(inst->n_variables, 0)];
        }
    }
    return fmi3OK;
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Int32 values[], size_t nValues)
{
    fmi3_instance *self = checked(instance, FMI3_CALL(fmi3GetInt32), valueReferences,
                                  nValueReferences, values, nValues, TYPE_INTEGER, 0);
    if (self == NULL)
        return fmi3Error;
    for (size_t i = 0; i < nValueReferences; ++i)
        values[i] = (fmi3Int32)self->core.values[valueReferences[i]];
    return fmi3OK;
}

fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Boolean values[], size_t nValues)
{
    fmi3_instance *self = checked(instance, FMI3_CALL(fmi3GetBoolean), valueReferences,
                                  nValueReferences, values, nValues, TYPE_BOOLEAN, 0);
    if (self == NULL)
        return fmi3Error;
    for (size_t i = 0; i < nValueReferences; ++i)
        values[i] = self->core.values[valueReferences[i]] != 0.0;
    return fmi3OK;
}

static double float64_at(const void *values, size_t i)
{
    return ((const fmi3Float64 *)values)[i];
}
static double int32_at(const void *values, size_t i)
{
    return (double)((const fmi3Int32 *)values)[i];
}
static double boolean_at(const void *values, size_t i)
{
    return ((const fmi3Boolean *)values)[i] ? 1.0 : 0.0;
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float64 values[], size_t nValues)
{
    fmi3_instance *self = checked(instance, FMI3_CALL(fmi3SetFloat64), valueReferences,
                                  nValueReferences, values, nValues, TYPE_REAL, 1);
    if (self == NULL ||
        fmu_check_reals(&self->core, "fmi3SetFloat64", valueReferences, nValueReferences,
                        values) != FMU_OK)
        return fmi3Error;
    return fmi3_status(fmu_store(&self->core, "fmi3SetFloat64", valueReferences,
                                 nValueReferences, values, float64_at));
}

fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Int32 values[], size_t nValues)
{
    fmi3_instance *self = checked(instance, FMI3_CALL(fmi3SetInt32), valueReferences,
                                  nValueReferences, values, nValues, TYPE_INTEGER, 1);
    if (self == NULL)
        return fmi3Error;
    return fmi3_status(fmu_store(&self->core, "fmi3SetInt32", valueReferences, nValueReferences,
                                 values, int32_at));
}

fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Boolean values[], size_t nValues)
{
    fmi3_instance *self = checked(instance, FMI3_CALL(fmi3SetBoolean), valueReferences,
                                  nValueReferences, values, nValues, TYPE_BOOLEAN, 1);
    if (self == NULL)
        return fmi3Error;
    return fmi3_status(fmu_store(&self->core, "fmi3SetBoolean", valueReferences,
                                 nValueReferences, values, boolean_at));
}

/* A type without variables: only an empty call succeeds; otherwise the message names the type
 * the first value reference really has. */
static fmi3Status no_variables_of_type(fmi3Instance instance, const char *function,
                                       unsigned allowed, const fmi3ValueReference vr[],
                                       size_t nvr)
{
    fmi3_instance *self = fmi3_checked(instance, function, allowed);
    if (self == NULL)
        return fmi3Error;
    if (nvr == 0)
        return fmi3OK;
    fmu_instance *inst = &self->core;
    if (vr == NULL)
        return fmi3_status(fmu_error(inst, "%s: the value reference array is NULL", function));
    int extra = extra_kind(inst, vr[0]);
    const model_variable *var = extra ? NULL : fmu_variable(inst, vr[0]);
    if (var == NULL && !extra)
        return fmi3_status(fmu_error(inst, "%s: unknown value reference %u", function, vr[0]));
    return fmi3_status(fmu_error(inst, "%s: variable %s (value reference %u) is of type %s",
                                 function, extra ? extra_name(extra) : var->name, vr[0],
                                 extra ? "Float64" : type_names[var->type]));
}

#define GETTER(TYPE, C_TYPE)                                                                   \
    fmi3Status fmi3Get##TYPE(fmi3Instance instance, const fmi3ValueReference valueReferences[], \
                             size_t nValueReferences, C_TYPE values[], size_t nValues)         \
    {                                                                                          \
        (void)values, (void)nValues;                                                           \
        return no_variables_of_type(instance, FMI3_CALL(fmi3Get##TYPE), valueReferences,      \
                                    nValueReferences);                                         \
    }
#define SETTER(TYPE, C_TYPE)                                                                   \
    fmi3Status fmi3Set##TYPE(fmi3Instance instance, const fmi3ValueReference valueReferences[], \
                             size_t nValueReferences, const C_TYPE values[], size_t nValues)   \
    {                                                                                          \
        (void)values, (void)nValues;                                                           \
        return no_variables_of_type(instance, FMI3_CALL(fmi3Set##TYPE), valueReferences,      \
                                    nValueReferences);                                         \
    }

GETTER(Float32, fmi3Float32)
GETTER(Int8, fmi3Int8)
GETTER(UInt8, fmi3UInt8)
GETTER(Int16, fmi3Int16)
GETTER(UInt16, fmi3UInt16)
GETTER(UInt32, fmi3UInt32)
GETTER(Int64, fmi3Int64)
GETTER(UInt64, fmi3UInt64)
GETTER(String, fmi3String)
SETTER(Float32, fmi3Float32)
SETTER(Int8, fmi3Int8)
SETTER(UInt8, fmi3UInt8)
SETTER(Int16, fmi3Int16)
SETTER(UInt16, fmi3UInt16)
SETTER(UInt32, fmi3UInt32)
SETTER(Int64, fmi3Int64)
SETTER(UInt64, fmi3UInt64)
SETTER(String, fmi3String)

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, size_t valueSizes[], fmi3Binary values[],
                         size_t nValues)
{
    (void)valueSizes, (void)values, (void)nValues;
    return no_variables_of_type(instance, FMI3_CALL(fmi3GetBinary), valueReferences,
                                nValueReferences);
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
    (void)valueSizes, (void)values, (void)nValues;
    return no_variables_of_type(instance, FMI3_CALL(fmi3SetBinary), valueReferences,
                                nValueReferences);
}

/* The index of the model's clock with value reference vr, or -1. */
static int clock_index(const fmu_instance *inst, fmi3ValueReference vr)
{
    for (size_t i = 0; i < inst->model->n_clocks; ++i)
        if (vr == fmi3_clock_vr(inst->n_variables, inst->model->n_event_indicators, i))
            return (int)i;
    return -1;
}

/* Output clocks: active in Event Mode while the internal event that ticks them is pending
 * (until fmi3UpdateDiscreteStates applies it); input clocks are ticked, never read back. */
fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Clock values[])
{
    fmi3_instance *self = fmi3_checked(instance, FMI3_CALL(fmi3GetClock));
    if (self == NULL)
        return fmi3Error;
    fmu_instance *inst = &self->core;
    if (nValueReferences > 0 && (valueReferences == NULL || values == NULL))
        return fmi3_status(fmu_error(inst, "fmi3GetClock: an array argument is NULL"));
    for (size_t i = 0; i < nValueReferences; ++i) {
        int clock = clock_index(inst, valueReferences[i]);
        if (clock < 0)
            return no_variables_of_type(instance, FMI3_CALL(fmi3GetClock), &valueReferences[i],
                                        1);
        const model_clock *declared = &inst->model->clocks[clock];
        if (declared->kind != CLOCK_OUTPUT)
            return fmi3_status(fmu_error(inst,
                                         "fmi3GetClock: value reference %u is an input clock "
                                         "(only output clocks are read)",
                                         valueReferences[i]));
        values[i] = inst->in_event_mode && inst->event_pending &&
                    inst->fired[declared->indicator];
    }
    return fmi3OK;
}

/* Ticks input clocks, in Event Mode only; the tick applies at fmi3UpdateDiscreteStates. */
fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Clock values[])
{
    fmi3_instance *self = fmi3_checked(instance, FMI3_CALL(fmi3SetClock));
    if (self == NULL)
        return fmi3Error;
    fmu_instance *inst = &self->core;
    if (nValueReferences > 0 && (valueReferences == NULL || values == NULL))
        return fmi3_status(fmu_error(inst, "fmi3SetClock: an array argument is NULL"));
    if (fmi3_mode_of(inst) != MODE_EVENT)
        return fmi3_status(fmu_error(inst, "fmi3SetClock: clocks tick in Event Mode only "
                                           "(the instance is in %s)",
                                     fmi3_mode_name(fmi3_mode_of(inst))));
    for (size_t i = 0; i < nValueReferences; ++i) {
        int clock = clock_index(inst, valueReferences[i]);
        if (clock < 0)
            return no_variables_of_type(instance, FMI3_CALL(fmi3SetClock), &valueReferences[i],
                                        1);
        if (inst->model->clocks[clock].kind == CLOCK_OUTPUT)
            return fmi3_status(fmu_error(inst, "fmi3SetClock: value reference %u is an output "
                                               "clock (the FMU ticks it)",
                                         valueReferences[i]));
    }
    for (size_t i = 0; i < nValueReferences; ++i)
        self->clock_active[clock_index(inst, valueReferences[i])] = values[i] ? 1 : 0;
    return fmi3OK;
}

/* The clocks' constant intervals and their shifts (0: every clock ticks from the start time),
 * as the description declares them; importers may ask in Initialization or Event Mode. */
fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[])
{
    fmi3_instance *self = fmi3_checked(instance, FMI3_CALL(fmi3GetIntervalDecimal));
    if (self == NULL)
        return fmi3Error;
    fmu_instance *inst = &self->core;
    if (nValueReferences > 0 && (valueReferences == NULL || intervals == NULL || qualifiers == NULL))
        return fmi3_status(fmu_error(inst, "fmi3GetIntervalDecimal: an array argument is NULL"));
    for (size_t i = 0; i < nValueReferences; ++i) {
        int clock = clock_index(inst, valueReferences[i]);
        if (clock < 0)
            return fmi3_status(fmu_error(inst, "fmi3GetIntervalDecimal: value reference %u is no "
                                               "clock",
                                         valueReferences[i]));
        model_clock_kind kind = inst->model->clocks[clock].kind;
        if (kind == CLOCK_COUNTDOWN || kind == CLOCK_CHANGING) {
            int changed = 0;
            intervals[i] = inst->model->clock_interval(inst->values, (size_t)clock, &changed);
            qualifiers[i] = changed ? fmi3IntervalChanged : fmi3IntervalUnchanged;
            continue;
        }
        if (kind != CLOCK_PERIODIC)
            return fmi3_status(fmu_error(inst, "fmi3GetIntervalDecimal: clock %u is triggered: "
                                               "it has no interval",
                                         valueReferences[i]));
        intervals[i] = inst->model->clocks[clock].interval;
        qualifiers[i] = fmi3IntervalChanged;
    }
    return fmi3OK;
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, fmi3Float64 shifts[])
{
    fmi3_instance *self = fmi3_checked(instance, FMI3_CALL(fmi3GetShiftDecimal));
    if (self == NULL)
        return fmi3Error;
    fmu_instance *inst = &self->core;
    if (nValueReferences > 0 && (valueReferences == NULL || shifts == NULL))
        return fmi3_status(fmu_error(inst, "fmi3GetShiftDecimal: an array argument is NULL"));
    for (size_t i = 0; i < nValueReferences; ++i) {
        if (clock_index(inst, valueReferences[i]) < 0)
            return fmi3_status(fmu_error(inst, "fmi3GetShiftDecimal: value reference %u is no "
                                               "clock",
                                         valueReferences[i]));
        shifts[i] = 0.0;
    }
    return fmi3OK;
}
