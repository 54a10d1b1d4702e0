/* The FMI 1.0 functions Co-Simulation and Model Exchange share: instantiation, logging, and
 * get and set served from the variable table. */
#include <string.h>

#include "fmi1_entry.h"
#include "fmu_guid.h"
#include "fmu_log.h"
#include "fmu_values.h"

/* Hands the core's message to the importer's FMI 1.0 logger, whose first argument is the
 * instance (NULL while it is instantiated). The message holds no printf conversion
 * (fmu_log.c), so it is the format itself. */
static void forward_log(const fmu_logging_callbacks *callbacks, const char *instance_name,
                        fmu_status status, const char *category, const char *message)
{
    fmi1CallbackLogger logger = (fmi1CallbackLogger)callbacks->logger;
    logger(callbacks->environment, instance_name, fmi1_status(status), category, message);
}

fmu_instance *fmi1_instantiate(const char *function, fmi1String instance_name, fmi1String guid,
                               fmi1CallbackLogger logger, fmi1Boolean logging_on)
{
    fmu_instance reporter = {
        .name = (char *)(instance_name ? instance_name : "(unnamed)"),
        .callbacks = {forward_log, (void (*)(void))logger, NULL},
        .logging_on = logging_on != fmi1False,
        .log_categories = LOG_ALL_CATEGORIES,
    };
    if (instance_name == NULL || instance_name[0] == '\0') {
        fmu_error(&reporter, "%s: the instance name is missing", function);
        return NULL;
    }
    char expected[FMU_GUID_LENGTH];
    fmu_guid(expected);
    if (guid == NULL || strcmp(guid, expected) != 0) {
        fmu_error(&reporter, "%s: GUID %s does not match this FMU's GUID %s", function,
                  guid ? guid : "(null)", expected);
        return NULL;
    }
    fmu_instance *inst = fmu_instance_create(&reporter, sizeof(fmu_instance), function);
    if (inst != NULL) {
        inst->callbacks.environment = inst;
    }
    return inst;
}

FMI1_ENTRY(const char *, fmiGetVersion)(void)
{
    return "1.0";
}

FMI1_ENTRY(fmi1Status, fmiSetDebugLogging)(fmi1Component c, fmi1Boolean loggingOn)
{
    fmu_instance *inst = fmu_checked(c, "fmiSetDebugLogging", PHASES_ANY);
    if (inst == NULL)
        return fmi1Error;
    return fmi1_status(
        fmu_set_logging(inst, "fmiSetDebugLogging", loggingOn != fmi1False, 0, NULL));
}

static fmu_instance *prepare_get(fmi1Component c, const char *function,
                                 const fmi1ValueReference vr[], size_t nvr, const void *value,
                                 variable_type type)
{
    fmu_instance *inst = fmu_checked(c, function, PHASES_ANY);
    if (inst == NULL || fmu_check_references(inst, function, vr, nvr, value, type) != FMU_OK ||
        fmu_prepare_read(inst, function) != FMU_OK)
        return NULL;
    return inst;
}

FMI1_ENTRY(fmi1Status, fmiGetReal)(fmi1Component c, const fmi1ValueReference vr[], size_t nvr,
                                   fmi1Real value[])
{
    fmu_instance *inst = prepare_get(c, "fmiGetReal", vr, nvr, value, TYPE_REAL);
    if (inst == NULL)
        return fmi1Error;
    for (size_t i = 0; i < nvr; ++i)
        value[i] = inst->values[vr[i]];
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiGetInteger)(fmi1Component c, const fmi1ValueReference vr[],
                                      size_t nvr, fmi1Integer value[])
{
    fmu_instance *inst = prepare_get(c, "fmiGetInteger", vr, nvr, value, TYPE_INTEGER);
    if (inst == NULL)
        return fmi1Error;
    for (size_t i = 0; i < nvr; ++i)
        value[i] = (fmi1Integer)inst->values[vr[i]];
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiGetBoolean)(fmi1Component c, const fmi1ValueReference vr[],
                                      size_t nvr, fmi1Boolean value[])
{
    fmu_instance *inst = prepare_get(c, "fmiGetBoolean", vr, nvr, value, TYPE_BOOLEAN);
    if (inst == NULL)
        return fmi1Error;
    for (size_t i = 0; i < nvr; ++i)
        value[i] = inst->values[vr[i]] != 0.0 ? fmi1True : fmi1False;
    return fmi1OK;
}

FMI1_ENTRY(fmi1Status, fmiGetString)(fmi1Component c, const fmi1ValueReference vr[],
                                     size_t nvr, fmi1String value[])
{
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmiGetString", PHASES_ANY);
    if (inst == NULL)
        return fmi1Error;
    if (nvr == 0)
        return fmi1OK;
    return fmi1_status(fmu_error(
        inst, "fmiGetString: unknown value reference %u (no String variables)", vr ? vr[0] : 0u));
}

static fmu_instance *prepare_set(fmi1Component c, const char *function,
                                 const fmi1ValueReference vr[], size_t nvr, const void *value,
                                 variable_type type)
{
    fmu_instance *inst = fmu_checked(c, function, PHASES_SETTABLE);
    if (inst == NULL || fmu_check_references(inst, function, vr, nvr, value, type) != FMU_OK)
        return NULL;
    return inst;
}

static double real_at(const void *values, size_t i) { return ((const fmi1Real *)values)[i]; }
static double integer_at(const void *values, size_t i)
{
    return (double)((const fmi1Integer *)values)[i];
}
static double boolean_at(const void *values, size_t i)
{
    return ((const fmi1Boolean *)values)[i] != fmi1False ? 1.0 : 0.0;
}

FMI1_ENTRY(fmi1Status, fmiSetReal)(fmi1Component c, const fmi1ValueReference vr[], size_t nvr,
                                   const fmi1Real value[])
{
    fmu_instance *inst = prepare_set(c, "fmiSetReal", vr, nvr, value, TYPE_REAL);
    if (inst == NULL || fmu_check_reals(inst, "fmiSetReal", vr, nvr, value) != FMU_OK)
        return fmi1Error;
    return fmi1_status(fmu_store(inst, "fmiSetReal", vr, nvr, value, real_at));
}

FMI1_ENTRY(fmi1Status, fmiSetInteger)(fmi1Component c, const fmi1ValueReference vr[],
                                      size_t nvr, const fmi1Integer value[])
{
    fmu_instance *inst = prepare_set(c, "fmiSetInteger", vr, nvr, value, TYPE_INTEGER);
    if (inst == NULL)
        return fmi1Error;
    return fmi1_status(fmu_store(inst, "fmiSetInteger", vr, nvr, value, integer_at));
}

FMI1_ENTRY(fmi1Status, fmiSetBoolean)(fmi1Component c, const fmi1ValueReference vr[],
                                      size_t nvr, const fmi1Boolean value[])
{
    fmu_instance *inst = prepare_set(c, "fmiSetBoolean", vr, nvr, value, TYPE_BOOLEAN);
    if (inst == NULL)
        return fmi1Error;
    return fmi1_status(fmu_store(inst, "fmiSetBoolean", vr, nvr, value, boolean_at));
}

FMI1_ENTRY(fmi1Status, fmiSetString)(fmi1Component c, const fmi1ValueReference vr[],
                                     size_t nvr, const fmi1String value[])
{
    (void)value;
    fmu_instance *inst = fmu_checked(c, "fmiSetString", PHASES_SETTABLE);
    if (inst == NULL)
        return fmi1Error;
    if (nvr == 0)
        return fmi1OK;
    return fmi1_status(fmu_error(
        inst, "fmiSetString: unknown value reference %u (no String variables)", vr ? vr[0] : 0u));
}
