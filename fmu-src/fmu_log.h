/* Logging through the master's callback, filtered by loggingOn and the log categories. */
#ifndef SYSSIMX_FMU_LOG_H
#define SYSSIMX_FMU_LOG_H

#include "fmu_instance.h"

typedef enum {
    LOG_EVENTS,
    LOG_STATUS_WARNING,
    LOG_STATUS_ERROR,
    LOG_ALL,
    LOG_CATEGORY_COUNT
} fmu_log_category;

extern const char *const fmu_log_category_names[LOG_CATEGORY_COUNT];
extern const char *const fmu_log_category_descriptions[LOG_CATEGORY_COUNT];

#define LOG_ALL_CATEGORIES ((1u << LOG_CATEGORY_COUNT) - 1u)

/* Errors and warnings reach the master unless their category was switched off explicitly;
 * information needs loggingOn as well, as FMI 2.0 calls it debug logging. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
void fmu_log(const fmu_instance *inst, fmu_status status, fmu_log_category category,
             const char *format, ...);

/* Shorthand for an error message; returns FMU_ERROR so callers can `return fmu_error(...)`. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
fmu_status fmu_error(const fmu_instance *inst, const char *format, ...);

/* Category bit for a name, or -1 when unknown. */
int fmu_log_category_from_name(const char *name);

/* Switches debug logging and selects the categories (none given: all); `function` names the
 * call in messages. */
fmu_status fmu_set_logging(fmu_instance *inst, const char *function, int logging_on,
                           size_t n_categories, const char *const categories[]);

#endif
