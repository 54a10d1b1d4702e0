/* A small FMI 3.0 Scheduled Execution FMU, for tests/python/test_fmi3_scheduled_execution.py
 * (modelDescription.xml beside it):
 *   tick     input Clock, tunable: its interval is the FMU's (0.5 s, 1 s from the second tick)
 *   later    input Clock, countdown: the tick partition announces it 0.25 s ahead at every odd
 *            tick
 *   alarm    output Clock: ticks with every third tick
 *   count    Int32, ticks of `tick`; laterCount Int32, ticks of `later`
 *   gain     Float64 input; sum Float64, the gains seen at the ticks of `tick`
 * Built to misbehave: SCHEDULED_UNBALANCED_LOCK unlocks preemption it never locked in the tick
 * partition; SCHEDULED_FAILS_AT_ONE returns fmi3Error from the partition at t >= 1.
 * It has only the functions an importer of Scheduled Execution calls. */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"

#define TOKEN "{3b0d6a52-6f0e-4c47-9d0c-2d2f1f8a7e11}"

enum { VR_TIME, VR_TICK, VR_LATER, VR_ALARM, VR_COUNT, VR_LATER_COUNT, VR_GAIN, VR_SUM };

typedef struct {
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback log;
    fmi3ClockUpdateCallback clock_update;
    fmi3LockPreemptionCallback lock;
    fmi3UnlockPreemptionCallback unlock;
    double interval;
    bool interval_changed;
    bool later_announced;
    bool alarm;
    int32_t count;
    int32_t later_count;
    double gain;
    double sum;
} model;

fmi3Instance fmi3InstantiateScheduledExecution(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instanceName, (void)resourcePath, (void)visible, (void)loggingOn;
    if (instantiationToken == NULL || strcmp(instantiationToken, TOKEN) != 0) {
        return NULL;
    }
    model *self = calloc(1, sizeof *self);
    if (self != NULL) {
        *self = (model){.environment = instanceEnvironment, .log = logMessage,
                        .clock_update = clockUpdate, .lock = lockPreemption,
                        .unlock = unlockPreemption, .interval = 0.5, .interval_changed = true};
    }
    return self;
}

void fmi3FreeInstance(fmi3Instance instance)
{
    free(instance);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    (void)instance, (void)toleranceDefined, (void)tolerance, (void)startTime,
        (void)stopTimeDefined, (void)stopTime;
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    (void)instance;
    return fmi3OK;
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    (void)instance;
    return fmi3OK;
}

static void tick_partition(model *self)
{
    self->lock();
    self->count++;
    self->sum += self->gain;
    self->unlock();
#ifdef SCHEDULED_UNBALANCED_LOCK
    self->unlock();
#endif
    if (self->count == 2) {
        self->interval = 1.0;
        self->interval_changed = true;
    }
    self->later_announced = self->count % 2 == 1;
    self->alarm = self->count % 3 == 0;
    if (self->later_announced || self->alarm) {
        self->clock_update(self->environment);
    }
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    model *self = instance;
#ifdef SCHEDULED_FAILS_AT_ONE
    if (activationTime >= 1.0) {
        return fmi3Error;
    }
#else
    (void)activationTime;
#endif
    switch (clockReference) {
    case VR_TICK:
        tick_partition(self);
        return fmi3OK;
    case VR_LATER:
        self->later_count++;
        return fmi3OK;
    default:
        return fmi3Error;
    }
}

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[])
{
    model *self = instance;
    for (size_t i = 0; i < nValueReferences; i++) {
        if (valueReferences[i] == VR_TICK) {
            qualifiers[i] = self->interval_changed ? fmi3IntervalChanged : fmi3IntervalUnchanged;
            intervals[i] = self->interval;
            self->interval_changed = false;
        } else if (valueReferences[i] == VR_LATER) {
            qualifiers[i] = self->later_announced ? fmi3IntervalChanged : fmi3IntervalNotYetKnown;
            intervals[i] = 0.25;
            self->later_announced = false;
        } else {
            return fmi3Error;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Clock values[])
{
    model *self = instance;
    for (size_t i = 0; i < nValueReferences; i++) {
        if (valueReferences[i] != VR_ALARM) {
            return fmi3Error;
        }
        values[i] = self->alarm;
        self->alarm = false;
    }
    return fmi3OK;
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Int32 values[], size_t nValues)
{
    model *self = instance;
    if (nValues != nValueReferences) {
        return fmi3Error;
    }
    for (size_t i = 0; i < nValueReferences; i++) {
        if (valueReferences[i] == VR_COUNT) {
            values[i] = self->count;
        } else if (valueReferences[i] == VR_LATER_COUNT) {
            values[i] = self->later_count;
        } else {
            return fmi3Error;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float64 values[], size_t nValues)
{
    model *self = instance;
    if (nValues != nValueReferences) {
        return fmi3Error;
    }
    for (size_t i = 0; i < nValueReferences; i++) {
        if (valueReferences[i] != VR_SUM) {
            return fmi3Error;
        }
        values[i] = self->sum;
    }
    return fmi3OK;
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float64 values[], size_t nValues)
{
    model *self = instance;
    if (nValues != nValueReferences) {
        return fmi3Error;
    }
    for (size_t i = 0; i < nValueReferences; i++) {
        if (valueReferences[i] != VR_GAIN) {
            return fmi3Error;
        }
        self->gain = values[i];
    }
    return fmi3OK;
}
