/* fmi2Get/Set/Free/Serialize/DeSerializeFMUstate: allowed in every phase but the fatal one. */
#include "fmi2_allowed.h"
#include "fmu_instance.h"
#include "fmu_state.h"

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetFMUstate));
    return inst ? fmu_state_get(inst, "fmi2GetFMUstate", FMUstate) : fmi2Error;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2SetFMUstate));
    return inst ? fmu_state_set(inst, "fmi2SetFMUstate", FMUstate) : fmi2Error;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2FreeFMUstate));
    return inst ? fmu_state_free(inst, "fmi2FreeFMUstate", FMUstate) : fmi2Error;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2SerializedFMUstateSize));
    return inst ? fmu_state_serialized_size(inst, "fmi2SerializedFMUstateSize", FMUstate, size)
                : fmi2Error;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[],
                                 size_t size)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2SerializeFMUstate));
    return inst ? fmu_state_serialize(inst, "fmi2SerializeFMUstate", FMUstate,
                                      (unsigned char *)serializedState, size)
                : fmi2Error;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2DeSerializeFMUstate));
    return inst ? fmu_state_deserialize(inst, "fmi2DeSerializeFMUstate",
                                        (const unsigned char *)serializedState, size, FMUstate)
                : fmi2Error;
}
