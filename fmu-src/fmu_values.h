/* Reading and writing variables by value reference, for every interface's get and set calls.
 * `function` names the call in messages. */
#ifndef SYSSIMX_FMU_VALUES_H
#define SYSSIMX_FMU_VALUES_H

#include "fmu_instance.h"

extern const char *const fmu_type_names[];

/* Refuses a value reference that is unknown or not of `type` (the message names it). */
fmu_status fmu_refuse_reference(const fmu_instance *inst, const char *function,
                                unsigned int vr);

/* Checks the arrays and every value reference before anything is read or written. */
fmu_status fmu_check_references(const fmu_instance *inst, const char *function,
                                const unsigned int vr[], size_t nvr, const void *value,
                                variable_type type);

/* Before values are read: the outputs follow the current state and inputs, and the model
 * allows reading now. */
fmu_status fmu_prepare_read(fmu_instance *inst, const char *function);

/* Stores nvr values, value_at(values, i) giving the i-th as a double. Checks every value
 * first (causality, variability, phase), so a refused call stores nothing; a changed value in
 * step mode restarts the integration there. */
fmu_status fmu_store(fmu_instance *inst, const char *function, const unsigned int vr[],
                     size_t nvr, const void *values, double (*value_at)(const void *, size_t));

/* Refuses a NaN among Real values to store. */
fmu_status fmu_check_reals(const fmu_instance *inst, const char *function,
                           const unsigned int vr[], size_t nvr, const double values[]);

#endif
