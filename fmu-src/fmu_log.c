#include "fmu_log.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *const fmu_log_category_names[LOG_CATEGORY_COUNT] = {
    "logEvents", "logStatusWarning", "logStatusError", "logAll"};

const char *const fmu_log_category_descriptions[LOG_CATEGORY_COUNT] = {
    "internal events located and handled by the FMU", "calls that return fmi2Warning",
    "calls that return fmi2Error", "every message"};

static int category_enabled(const fmu_instance *inst, fmu_status status,
                            fmu_log_category category)
{
    unsigned bit = 1u << category;
    unsigned all = 1u << LOG_ALL;
    int enabled = (inst->log_categories & (bit | all)) != 0;
    if (status >= FMU_WARNING)
        return enabled;
    return inst->logging_on && enabled;
}

static void emit(const fmu_instance *inst, fmu_status status, fmu_log_category category,
                 const char *format, va_list args)
{
    if (inst == NULL || inst->callbacks.logger == NULL || !category_enabled(inst, status, category))
        return;
    char message[1024];
    vsnprintf(message, sizeof message, format, args);
    /* The master may treat the message as a printf format: keep it free of conversions. */
    for (char *c = message; *c != '\0'; ++c)
        if (*c == '%')
            *c = ' ';
    inst->callbacks.forward(&inst->callbacks, inst->name, status,
                            fmu_log_category_names[category], message);
}

void fmu_log(const fmu_instance *inst, fmu_status status, fmu_log_category category,
             const char *format, ...)
{
    va_list args;
    va_start(args, format);
    emit(inst, status, category, format, args);
    va_end(args);
}

fmu_status fmu_error(const fmu_instance *inst, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    emit(inst, FMU_ERROR, LOG_STATUS_ERROR, format, args);
    va_end(args);
    return FMU_ERROR;
}

int fmu_log_category_from_name(const char *name)
{
    for (int i = 0; i < LOG_CATEGORY_COUNT; ++i)
        if (name != NULL && strcmp(name, fmu_log_category_names[i]) == 0)
            return i;
    return -1;
}

fmu_status fmu_set_logging(fmu_instance *inst, const char *function, int logging_on,
                           size_t n_categories, const char *const categories[])
{
    unsigned selected = 0;
    for (size_t i = 0; i < n_categories; ++i) {
        int category = fmu_log_category_from_name(categories ? categories[i] : NULL);
        if (category < 0)
            return fmu_error(inst, "%s: unknown log category \"%s\"", function,
                             categories && categories[i] ? categories[i] : "(null)");
        selected |= 1u << category;
    }
    inst->logging_on = logging_on;
    inst->log_categories = n_categories > 0 ? selected : LOG_ALL_CATEGORIES;
    return FMU_OK;
}
