/* FMI 1.0 entry points: named <modelIdentifier>_fmiXxx (FMI 1.0 prefixes every function with
 * the model identifier; the build defines MODEL_IDENTIFIER) and exported from the hidden rest. */
#ifndef SYSSIMX_FMI1_ENTRY_H
#define SYSSIMX_FMI1_ENTRY_H

#include <stddef.h> /* fmi1Functions.h uses size_t without including it */

#include "fmi1Functions.h"
#include "fmu_instance.h"

#ifndef MODEL_IDENTIFIER
#error "an FMI 1.0 build defines MODEL_IDENTIFIER, the prefix of its function names"
#endif

#define FMI1_JOIN(prefix, name) prefix##_##name
#define FMI1_PREFIXED(prefix, name) FMI1_JOIN(prefix, name)
#define FMI1_EXPORT __attribute__((visibility("default")))
/* The definition of entry point `name` ("fmiDoStep" -> <id>_fmiDoStep). */
#define FMI1_ENTRY(type, name) FMI1_EXPORT type FMI1_PREFIXED(MODEL_IDENTIFIER, name)

/* The core's status as FMI 1.0's: the boundary every fmi1 entry point returns through. */
static inline fmi1Status fmi1_status(fmu_status status)
{
    switch (status) {
    case FMU_OK: return fmi1OK;
    case FMU_WARNING: return fmi1Warning;
    case FMU_DISCARD: return fmi1Discard;
    case FMU_ERROR: break;
    case FMU_FATAL: return fmi1Fatal;
    }
    return fmi1Error;
}

/* A new instance for an FMI 1.0 instantiate call: the core's logger gets the instance as FMI
 * 1.0's fmiComponent. NULL after logging why. */
fmu_instance *fmi1_instantiate(const char *function, fmi1String instance_name, fmi1String guid,
                               fmi1CallbackLogger logger, fmi1Boolean logging_on);

#endif
