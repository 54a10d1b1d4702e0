/* fmi3Get/Set/Free/Serialize/DeserializeFMUState: allowed in every state but the fatal one.
 * A state carries the event mode and a pending internal event with it. */
#include "fmi3_allowed.h"
#include "fmi3_instance.h"
#include "fmu_state.h"

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3GetFMUState));
    return inst ? fmi3_status(fmu_state_get(&inst->core, "fmi3GetFMUState", FMUState))
                : fmi3Error;
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3SetFMUState));
    return inst ? fmi3_status(fmu_state_set(&inst->core, "fmi3SetFMUState", FMUState))
                : fmi3Error;
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3FreeFMUState));
    return inst ? fmi3_status(fmu_state_free(&inst->core, "fmi3FreeFMUState", FMUState))
                : fmi3Error;
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t *size)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3SerializedFMUStateSize));
    return inst ? fmi3_status(fmu_state_serialized_size(
                      &inst->core, "fmi3SerializedFMUStateSize", FMUState, size))
                : fmi3Error;
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                 fmi3Byte serializedState[], size_t size)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3SerializeFMUState));
    return inst ? fmi3_status(fmu_state_serialize(&inst->core, "fmi3SerializeFMUState",
                                                  FMUState, serializedState, size))
                : fmi3Error;
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                   size_t size, fmi3FMUState *FMUState)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3DeserializeFMUState));
    return inst ? fmi3_status(fmu_state_deserialize(&inst->core, "fmi3DeserializeFMUState",
                                                    serializedState, size, FMUState))
                : fmi3Error;
}
