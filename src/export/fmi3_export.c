/* The FMI 3.0 Co-Simulation entry points of an exported system (exported_system.h): Float64
 * inputs, outputs and parameters, the event count as an Int32 output, early return at the
 * events located inside when the importer allows it, event mode (in which nothing is left to
 * do: the system handled its events inside doStep). */
#include "fmi3_export.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const fmi3ValueReference time_vr = 0; /* the independent variable */

static void log_to_importer(void *user, int error, const char *message)
{
    fmi3_instance *instance = user;
    if (instance->log_message != NULL && (error || instance->logging_on)) {
        instance->log_message(instance->environment, error ? fmi3Error : fmi3OK,
                              error ? "logStatusError" : "logAll", message);
    }
}

fmi3Status fmi3_refuse(fmi3Instance instance, const char *what)
{
    if (instance == NULL) {
        return fmi3Error;
    }
    log_to_importer(instance, 1, what);
    return fmi3Error;
}

const char *fmi3GetVersion(void)
{
    return fmi3Version;
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate)
{
    (void)instanceName, (void)visible, (void)requiredIntermediateVariables,
        (void)intermediateUpdate;
    fmi3_instance *instance = calloc(1, sizeof *instance);
    if (instance == NULL) {
        return NULL;
    }
    instance->environment = instanceEnvironment;
    instance->log_message = logMessage;
    instance->logging_on = loggingOn;
    instance->event_mode_used = eventModeUsed;
    instance->early_return_allowed = earlyReturnAllowed;
    if (resourcePath == NULL || nRequiredIntermediateVariables > 0) {
        log_to_importer(instance, 1,
                        resourcePath == NULL
                            ? "fmi3InstantiateCoSimulation: no resource path"
                            : "fmi3InstantiateCoSimulation: no variable is an intermediate one");
    } else {
        /* the path ends in '/'; the system names its files below it */
        size_t length = strlen(resourcePath);
        char *folder = malloc(length + 1);
        if (folder != NULL) {
            memcpy(folder, resourcePath, length + 1);
            while (length > 1 && folder[length - 1] == '/') {
                folder[--length] = '\0';
            }
            instance->system =
                exported_system_new(folder, instantiationToken, log_to_importer, instance);
            free(folder);
            if (instance->system != NULL) {
                exported_system_stop_at_own_events(instance->system, earlyReturnAllowed);
            }
        }
    }
    if (instance->system == NULL) {
        free(instance);
        return NULL;
    }
    return instance;
}

void fmi3FreeInstance(fmi3Instance instance)
{
    fmi3_instance *inst = instance;
    if (inst != NULL) {
        exported_system_free(inst->system);
        free(inst);
    }
}

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    (void)nCategories, (void)categories;
    fmi3_instance *inst = instance;
    if (inst == NULL) {
        return fmi3Error;
    }
    inst->logging_on = loggingOn;
    return fmi3OK;
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    /* the members keep the tolerances the system was exported with */
    (void)toleranceDefined, (void)tolerance, (void)stopTimeDefined, (void)stopTime;
    fmi3_instance *inst = instance;
    if (inst == NULL) {
        return fmi3Error;
    }
    if (inst->mode != MODE3_INSTANTIATED) {
        return fmi3_refuse(inst, "fmi3EnterInitializationMode: only once, after instantiation");
    }
    if (exported_system_start(inst->system, startTime) != 0) {
        inst->mode = MODE3_ERROR;
        return fmi3Error;
    }
    inst->mode = MODE3_INITIALIZATION;
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    fmi3_instance *inst = instance;
    if (inst == NULL) {
        return fmi3Error;
    }
    if (inst->mode != MODE3_INITIALIZATION) {
        return fmi3_refuse(inst, "fmi3ExitInitializationMode: not in initialization mode");
    }
    exported_system_steps(inst->system);
    inst->mode = inst->event_mode_used ? MODE3_EVENT : MODE3_STEP;
    return fmi3OK;
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
    fmi3_instance *inst = instance;
    if (inst == NULL) {
        return fmi3Error;
    }
    if (inst->mode != MODE3_STEP && inst->mode != MODE3_EVENT) {
        return fmi3_refuse(inst, "fmi3EnterEventMode: only from step mode");
    }
    inst->mode = MODE3_EVENT;
    return fmi3OK;
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined, fmi3Float64 *nextEventTime)
{
    fmi3_instance *inst = instance;
    if (inst == NULL) {
        return fmi3Error;
    }
    if (inst->mode != MODE3_EVENT) {
        return fmi3_refuse(inst, "fmi3UpdateDiscreteStates: only in event mode");
    }
    /* the events inside were handled where they were located: nothing is left to update */
    fmi3Boolean *flags[] = {discreteStatesNeedUpdate, nominalsOfContinuousStatesChanged,
                            valuesOfContinuousStatesChanged, nextEventTimeDefined};
    for (size_t k = 0; k < sizeof flags / sizeof flags[0]; k++) {
        if (flags[k] != NULL) {
            *flags[k] = fmi3False;
        }
    }
    if (terminateSimulation != NULL) {
        *terminateSimulation = inst->terminated_by_member ? fmi3True : fmi3False;
    }
    if (nextEventTime != NULL) {
        *nextEventTime = 0.0;
    }
    return fmi3OK;
}

fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{
    fmi3_instance *inst = instance;
    if (inst == NULL) {
        return fmi3Error;
    }
    if (inst->mode != MODE3_EVENT) {
        return fmi3_refuse(inst, "fmi3EnterStepMode: only from event mode");
    }
    inst->mode = MODE3_STEP;
    return fmi3OK;
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    fmi3_instance *inst = instance;
    if (inst == NULL) {
        return fmi3Error;
    }
    inst->mode = MODE3_TERMINATED;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance instance)
{
    fmi3_instance *inst = instance;
    if (inst == NULL) {
        return fmi3Error;
    }
    exported_system_reset(inst->system);
    inst->mode = MODE3_INSTANTIATED;
    inst->terminated_by_member = 0;
    return fmi3OK;
}

static int scalars(fmi3_instance *inst, size_t nValueReferences, size_t nValues, const void *vr,
                   const void *values)
{
    if (nValueReferences > 0 && (vr == NULL || values == NULL)) {
        return 0;
    }
    if (nValues != nValueReferences) {
        fmi3_refuse(inst, "every variable of this FMU is a scalar: nValues must equal "
                          "nValueReferences");
        return 0;
    }
    return 1;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float64 values[], size_t nValues)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || !scalars(inst, nValueReferences, nValues, valueReferences, values)) {
        return fmi3Error;
    }
    for (size_t k = 0; k < nValueReferences; k++) {
        int result =
            valueReferences[k] == time_vr
                ? (values[k] = exported_system_time(inst->system), 0)
                : exported_system_get_real(inst->system, &valueReferences[k], 1, &values[k]);
        if (result != 0) {
            return fmi3Error;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float64 values[], size_t nValues)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || !scalars(inst, nValueReferences, nValues, valueReferences, values)) {
        return fmi3Error;
    }
    return exported_system_set_real(inst->system, valueReferences, nValueReferences, values) == 0
               ? fmi3OK
               : fmi3Error;
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Int32 values[], size_t nValues)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || !scalars(inst, nValueReferences, nValues, valueReferences, values)) {
        return fmi3Error;
    }
    for (size_t k = 0; k < nValueReferences; k++) {
        int value;
        if (exported_system_get_integer(inst->system, &valueReferences[k], 1, &value, 0) != 0) {
            return fmi3Error;
        }
        values[k] = value;
    }
    return fmi3OK;
}

fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Int32 values[], size_t nValues)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || !scalars(inst, nValueReferences, nValues, valueReferences, values)) {
        return fmi3Error;
    }
    for (size_t k = 0; k < nValueReferences; k++) {
        int value = values[k];
        if (exported_system_set_integer(inst->system, &valueReferences[k], 1, &value, 0) != 0) {
            return fmi3Error;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Boolean values[], size_t nValues)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || !scalars(inst, nValueReferences, nValues, valueReferences, values)) {
        return fmi3Error;
    }
    for (size_t k = 0; k < nValueReferences; k++) {
        int value;
        if (exported_system_get_integer(inst->system, &valueReferences[k], 1, &value, 1) != 0) {
            return fmi3Error;
        }
        values[k] = value != 0;
    }
    return fmi3OK;
}

fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Boolean values[], size_t nValues)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || !scalars(inst, nValueReferences, nValues, valueReferences, values)) {
        return fmi3Error;
    }
    for (size_t k = 0; k < nValueReferences; k++) {
        int value = values[k];
        if (exported_system_set_integer(inst->system, &valueReferences[k], 1, &value, 1) != 0) {
            return fmi3Error;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || FMUState == NULL) {
        return fmi3Error;
    }
    exported_state *state = exported_state_save(inst->system);
    if (state == NULL) {
        return fmi3Error;
    }
    exported_state_free(*FMUState);
    *FMUState = state;
    return fmi3OK;
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || FMUState == NULL) {
        return fmi3Error;
    }
    if (exported_state_restore(inst->system, FMUState) != 0) {
        return fmi3Error;
    }
    inst->terminated_by_member = 0;
    return fmi3OK;
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    if (instance == NULL || FMUState == NULL) {
        return fmi3Error;
    }
    exported_state_free(*FMUState);
    *FMUState = NULL;
    return fmi3OK;
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t *size)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || FMUState == NULL || size == NULL) {
        return fmi3Error;
    }
    unsigned char *bytes = exported_state_serialize(inst->system, FMUState, size);
    free(bytes);
    return bytes != NULL ? fmi3OK : fmi3Error;
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                 fmi3Byte serializedState[], size_t size)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || FMUState == NULL || serializedState == NULL) {
        return fmi3Error;
    }
    size_t needed = 0;
    unsigned char *bytes = exported_state_serialize(inst->system, FMUState, &needed);
    if (bytes == NULL) {
        return fmi3Error;
    }
    fmi3Status status = fmi3OK;
    if (needed > size) {
        status = fmi3_refuse(inst, "fmi3SerializeFMUState: the buffer is smaller than "
                                   "fmi3SerializedFMUStateSize said");
    } else {
        memcpy(serializedState, bytes, needed);
    }
    free(bytes);
    return status;
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                   size_t size, fmi3FMUState *FMUState)
{
    fmi3_instance *inst = instance;
    if (inst == NULL || serializedState == NULL || FMUState == NULL) {
        return fmi3Error;
    }
    exported_state *state = exported_state_deserialize(inst->system, serializedState, size);
    if (state == NULL) {
        return fmi3Error;
    }
    exported_state_free(*FMUState);
    *FMUState = state;
    return fmi3OK;
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    fmi3_instance *inst = instance;
    if (inst == NULL || eventHandlingNeeded == NULL || terminateSimulation == NULL ||
        earlyReturn == NULL || lastSuccessfulTime == NULL) {
        return fmi3Error;
    }
    if (inst->mode != MODE3_STEP || inst->terminated_by_member) {
        return fmi3_refuse(inst, inst->terminated_by_member
                                     ? "fmi3DoStep: a member ended the simulation"
                                     : "fmi3DoStep: not in step mode (initialize first)");
    }
    if (!(communicationStepSize > 0.0)) {
        return fmi3_refuse(inst, "fmi3DoStep: the step size must be positive");
    }
    double reached;
    int returned_early;
    int result =
        exported_system_step(inst->system, currentCommunicationPoint, communicationStepSize,
                             inst->early_return_allowed, &reached, &returned_early);
    /* the events inside were handled there: the importer has none to handle */
    *eventHandlingNeeded = fmi3False;
    *earlyReturn = returned_early ? fmi3True : fmi3False;
    *lastSuccessfulTime = reached;
    *terminateSimulation = result == 1 ? fmi3True : fmi3False;
    if (result == 1) {
        inst->terminated_by_member = 1;
        return fmi3OK;
    }
    if (result != 0) {
        inst->mode = MODE3_ERROR;
        return fmi3Error;
    }
    return fmi3OK;
}
