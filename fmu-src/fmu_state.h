/* FMU states (snapshots of an instance) for every interface; `function` names the call in
 * messages. The serialized form carries the model's GUID, so another model's bytes are refused. */
#ifndef SYSSIMX_FMU_STATE_H
#define SYSSIMX_FMU_STATE_H

#include <stddef.h>

#include "fmu_instance.h"

/* Captures the instance into *FMUstate, reusing it when it is a state of this FMU. */
fmu_status fmu_state_get(fmu_instance *inst, const char *function, void **FMUstate);
fmu_status fmu_state_set(fmu_instance *inst, const char *function, const void *FMUstate);
fmu_status fmu_state_free(fmu_instance *inst, const char *function, void **FMUstate);
fmu_status fmu_state_serialized_size(fmu_instance *inst, const char *function,
                                     const void *FMUstate, size_t *size);
fmu_status fmu_state_serialize(fmu_instance *inst, const char *function, const void *FMUstate,
                               unsigned char serializedState[], size_t size);
fmu_status fmu_state_deserialize(fmu_instance *inst, const char *function,
                                 const unsigned char serializedState[], size_t size,
                                 void **FMUstate);

#endif
