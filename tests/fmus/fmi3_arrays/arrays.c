/* A small FMI 3.0 Co-Simulation FMU with arrays, for the import tests (modelDescription.xml
 * beside it):
 *   n         UInt64 structural parameter, 3: the size of u, k, y and positive
 *   u[n]      Float64 input
 *   k[n]      Float64 tunable parameter
 *   y[n]      Float64 output, y = k * u element by element
 *   positive  Boolean output array, y > 0
 *   m[2][2]   Int32 tunable parameter, row-major
 *   order     Int32 output, 10 * m[0][1] + m[1][0] (tells the row-major order)
 *   big       Int64 output, 2^32 + the number of steps done (beyond a C int)
 *   writes    Int32 output, how many fmi3SetFloat64 calls wrote u (one per importer's write)
 *   wide      UInt64 output, 2^40 * |u[0]| (beyond 2^53 from |u[0]| = 2^13 + 1)
 * Every array is read and written whole: one value reference, all its values. The structural
 * parameter cannot change (no configuration mode). */
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"

#define TOKEN "{8c4e810f-3df3-4a00-8276-176fa3c9f003}"

enum { N = 3 };
enum { VR_TIME, VR_N, VR_U, VR_K, VR_Y, VR_BIG, VR_M, VR_ORDER, VR_POSITIVE, VR_WRITES, VR_WIDE };

typedef struct {
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback log;
    double time;
    double u[N];
    double k[N];
    int32_t m[4];
    uint64_t steps;
    int32_t writes;
} model;

static void say(model *self, const char *format, ...)
{
    if (self->log == NULL) {
        return;
    }
    char message[256];
    va_list args;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    self->log(self->environment, fmi3Error, "logStatusError", message);
}

/* ------------------------------------------------------------------ life cycle */

const char *fmi3GetVersion(void)
{
    return fmi3Version;
}

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    (void)instance, (void)loggingOn, (void)nCategories, (void)categories;
    return fmi3OK;
}

static void start(model *self)
{
    static const double k[N] = {1.0, 2.0, 3.0};
    static const int32_t m[4] = {1, 2, 3, 4};
    self->time = 0.0;
    memset(self->u, 0, sizeof self->u);
    memcpy(self->k, k, sizeof self->k);
    memcpy(self->m, m, sizeof self->m);
    self->steps = 0;
    self->writes = 0;
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate)
{
    (void)instanceName, (void)resourcePath, (void)visible, (void)loggingOn,
        (void)earlyReturnAllowed, (void)requiredIntermediateVariables,
        (void)nRequiredIntermediateVariables, (void)intermediateUpdate;
    model probe = {instanceEnvironment, logMessage, 0.0, {0}, {0}, {0}, 0, 0};
#ifdef FMI3_FOREIGN_ENVIRONMENT
    /* as the binaries of FMPy's FMI 3.0 containers, whose descriptions have an empty token */
    bool token_accepted = instantiationToken != NULL &&
        (instantiationToken[0] == '\0' || strcmp(instantiationToken, TOKEN) == 0);
#else
    bool token_accepted = instantiationToken != NULL && strcmp(instantiationToken, TOKEN) == 0;
#endif
    if (!token_accepted) {
        say(&probe, "wrong instantiation token");
        return NULL;
    }
    if (eventModeUsed) {
        say(&probe, "this FMU has no event mode");
        return NULL;
    }
    model *self = malloc(sizeof *self);
    if (self != NULL) {
        *self = probe;
        start(self);
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
    (void)toleranceDefined, (void)tolerance, (void)stopTimeDefined, (void)stopTime;
    ((model *)instance)->time = startTime;
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

fmi3Status fmi3Reset(fmi3Instance instance)
{
    start(instance);
    return fmi3OK;
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    model *self = instance;
    self->time = currentCommunicationPoint + communicationStepSize;
    self->steps += 1;
    *eventHandlingNeeded = fmi3False;
    *terminateSimulation = fmi3False;
    *earlyReturn = fmi3False;
    *lastSuccessfulTime = self->time;
#ifdef FMI3_FOREIGN_ENVIRONMENT
    if (self->log != NULL) { /* an environment not the one it was given */
        self->log((fmi3InstanceEnvironment)1, fmi3OK, "logAll", "stepped naming environment 1");
    }
#endif
#ifdef FMI3_MISBEHAVES
    if (currentCommunicationPoint >= 0.45) { /* claims a time past the step's end */
        *earlyReturn = fmi3True;
        *lastSuccessfulTime = self->time + communicationStepSize;
    }
#endif
    return fmi3OK;
}

/* ------------------------------------------------------------------ values */

/* Whether the values of vr[0..n) fill nValues exactly, given each one's count. */
static bool counts_match(model *self, const char *function, const fmi3ValueReference vr[], size_t n,
                         size_t nValues, size_t (*count)(fmi3ValueReference))
{
    size_t total = 0;
    for (size_t i = 0; i < n; ++i) {
        size_t c = count(vr[i]);
        if (c == 0) {
            say(self, "%s: value reference %u is not a variable of this type", function, vr[i]);
            return false;
        }
        total += c;
    }
    if (total != nValues) {
        say(self, "%s: the value references hold %zu values, nValues is %zu", function, total,
            nValues);
        return false;
    }
    return true;
}

static size_t float64_count(fmi3ValueReference vr)
{
    return vr == VR_TIME ? 1 : vr == VR_U || vr == VR_K || vr == VR_Y ? N : 0;
}

static size_t int32_count(fmi3ValueReference vr)
{
    return vr == VR_M ? 4 : vr == VR_ORDER || vr == VR_WRITES ? 1 : 0;
}

static size_t int64_count(fmi3ValueReference vr)
{
    return vr == VR_BIG;
}

static size_t uint64_count(fmi3ValueReference vr)
{
    return vr == VR_N || vr == VR_WIDE;
}

static size_t boolean_count(fmi3ValueReference vr)
{
    return vr == VR_POSITIVE ? N : 0;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                          fmi3Float64 values[], size_t nValues)
{
    model *self = instance;
    if (!counts_match(self, "fmi3GetFloat64", vr, n, nValues, float64_count)) {
        return fmi3Error;
    }
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] == VR_TIME) {
            *values++ = self->time;
            continue;
        }
        for (size_t j = 0; j < N; ++j) {
            *values++ = vr[i] == VR_U   ? self->u[j]
                        : vr[i] == VR_K ? self->k[j]
                                        : self->k[j] * self->u[j];
        }
    }
    return fmi3OK;
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                          const fmi3Float64 values[], size_t nValues)
{
    model *self = instance;
    if (!counts_match(self, "fmi3SetFloat64", vr, n, nValues, float64_count)) {
        return fmi3Error;
    }
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] != VR_U && vr[i] != VR_K) {
            say(self, "fmi3SetFloat64: value reference %u cannot be set", vr[i]);
            return fmi3Error;
        }
        memcpy(vr[i] == VR_U ? self->u : self->k, values, N * sizeof *values);
        values += N;
        self->writes += vr[i] == VR_U;
    }
    return fmi3OK;
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                        fmi3Int32 values[], size_t nValues)
{
    model *self = instance;
    if (!counts_match(self, "fmi3GetInt32", vr, n, nValues, int32_count)) {
        return fmi3Error;
    }
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] == VR_M) {
            memcpy(values, self->m, sizeof self->m);
            values += 4;
        } else {
            *values++ = vr[i] == VR_ORDER ? 10 * self->m[1] + self->m[2] : self->writes;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                        const fmi3Int32 values[], size_t nValues)
{
    model *self = instance;
    if (!counts_match(self, "fmi3SetInt32", vr, n, nValues, int32_count)) {
        return fmi3Error;
    }
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] != VR_M) {
            say(self, "fmi3SetInt32: value reference %u cannot be set", vr[i]);
            return fmi3Error;
        }
        memcpy(self->m, values, sizeof self->m);
        values += 4;
    }
    return fmi3OK;
}

fmi3Status fmi3GetInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                        fmi3Int64 values[], size_t nValues)
{
    model *self = instance;
    if (!counts_match(self, "fmi3GetInt64", vr, n, nValues, int64_count)) {
        return fmi3Error;
    }
    for (size_t i = 0; i < n; ++i) {
        values[i] = ((int64_t)1 << 32) + (int64_t)self->steps;
    }
    return fmi3OK;
}

fmi3Status fmi3SetInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                        const fmi3Int64 values[], size_t nValues)
{
    (void)values;
    model *self = instance;
    if (n > 0 && counts_match(self, "fmi3SetInt64", vr, n, nValues, int64_count)) {
        say(self, "fmi3SetInt64: big is an output");
    }
    return n > 0 ? fmi3Error : fmi3OK;
}

fmi3Status fmi3GetUInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                         fmi3UInt64 values[], size_t nValues)
{
    model *self = instance;
    if (!counts_match(self, "fmi3GetUInt64", vr, n, nValues, uint64_count)) {
        return fmi3Error;
    }
    for (size_t i = 0; i < n; ++i) {
        values[i] = vr[i] == VR_N ? N : ((uint64_t)1 << 40) * (uint64_t)fabs(self->u[0]);
    }
    return fmi3OK;
}

fmi3Status fmi3SetUInt64(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                         const fmi3UInt64 values[], size_t nValues)
{
    model *self = instance;
    if (!counts_match(self, "fmi3SetUInt64", vr, n, nValues, uint64_count)) {
        return fmi3Error;
    }
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] == VR_WIDE) {
            say(self, "fmi3SetUInt64: wide is an output");
            return fmi3Error;
        }
        if (values[i] != N) {
            say(self, "fmi3SetUInt64: n is a structural parameter fixed at %d", N);
            return fmi3Error;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                          fmi3Boolean values[], size_t nValues)
{
    model *self = instance;
    if (!counts_match(self, "fmi3GetBoolean", vr, n, nValues, boolean_count)) {
        return fmi3Error;
    }
    for (size_t i = 0; i < n; ++i) {
        for (size_t j = 0; j < N; ++j) {
            *values++ = self->k[j] * self->u[j] > 0.0;
        }
    }
    return fmi3OK;
}

fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                          const fmi3Boolean values[], size_t nValues)
{
    (void)vr, (void)values, (void)nValues;
    if (n > 0) {
        say(instance, "fmi3SetBoolean: positive is an output");
    }
    return n > 0 ? fmi3Error : fmi3OK;
}

/* The types no variable has: any value reference is an error. */
static fmi3Status no_variable(fmi3Instance instance, const char *function,
                              const fmi3ValueReference vr[], size_t n)
{
    if (n == 0) {
        return fmi3OK;
    }
    say(instance, "%s: value reference %u is not a variable of this type", function, vr[0]);
    return fmi3Error;
}

#define NO_VARIABLES(type) \
    fmi3Status fmi3Get##type(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, \
                             fmi3##type values[], size_t nValues) \
    { \
        (void)values, (void)nValues; \
        return no_variable(instance, "fmi3Get" #type, vr, n); \
    } \
    fmi3Status fmi3Set##type(fmi3Instance instance, const fmi3ValueReference vr[], size_t n, \
                             const fmi3##type values[], size_t nValues) \
    { \
        (void)values, (void)nValues; \
        return no_variable(instance, "fmi3Set" #type, vr, n); \
    }

NO_VARIABLES(Float32)
NO_VARIABLES(Int8)
NO_VARIABLES(UInt8)
NO_VARIABLES(Int16)
NO_VARIABLES(UInt16)
NO_VARIABLES(UInt32)
NO_VARIABLES(String)

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                         size_t valueSizes[], fmi3Binary values[], size_t nValues)
{
#ifdef FMI3_MISBEHAVES
    const model *self = instance;
    /* "blob": no data, but a size, at t = 0.3 only (a run from 0.4 meets the early return) */
    static const fmi3Byte blob[] = {0x01, 0x02};
    if (n == 1 && nValues == 1 && vr[0] == 11) {
        const int lies = self->time > 0.25 && self->time < 0.35;
        values[0] = lies ? NULL : blob;
        valueSizes[0] = lies ? 4096 : sizeof blob;
        return fmi3OK;
    }
#endif
    (void)valueSizes, (void)values, (void)nValues;
    return no_variable(instance, "fmi3GetBinary", vr, n);
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t n,
                         const size_t valueSizes[], const fmi3Binary values[], size_t nValues)
{
    (void)valueSizes, (void)values, (void)nValues;
    return no_variable(instance, "fmi3SetBinary", vr, n);
}

/* ------------------------------------------------------------------ no event mode */

fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
    say(instance, "fmi3EnterEventMode: this FMU has no event mode");
    return fmi3Error;
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined, fmi3Float64 *nextEventTime)
{
    (void)discreteStatesNeedUpdate, (void)terminateSimulation,
        (void)nominalsOfContinuousStatesChanged, (void)valuesOfContinuousStatesChanged,
        (void)nextEventTimeDefined, (void)nextEventTime;
    say(instance, "fmi3UpdateDiscreteStates: this FMU has no event mode");
    return fmi3Error;
}

fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{
    say(instance, "fmi3EnterStepMode: this FMU has no event mode");
    return fmi3Error;
}

/* ------------------------------------------------------------------ what this FMU lacks */

/* Model Exchange, Scheduled Execution, clocks, configuration mode, states, derivatives and
 * dependencies: FMI 3.0 has every binary export them; each one here refuses by name. */
static fmi3Status unsupported(fmi3Instance instance, const char *function)
{
    say(instance, "%s is not supported by this FMU", function);
    return fmi3Error;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)instanceName, (void)instantiationToken, (void)resourcePath, (void)visible,
        (void)loggingOn, (void)instanceEnvironment, (void)logMessage;
    return NULL;
}

fmi3Instance fmi3InstantiateScheduledExecution(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instanceName, (void)instantiationToken, (void)resourcePath, (void)visible,
        (void)loggingOn, (void)instanceEnvironment, (void)logMessage, (void)clockUpdate,
        (void)lockPreemption, (void)unlockPreemption;
    return NULL;
}

fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Clock values[])
{
    (void)valueReferences, (void)nValueReferences, (void)values;
    return unsupported(instance, "fmi3GetClock");
}

fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Clock values[])
{
    (void)valueReferences, (void)nValueReferences, (void)values;
    return unsupported(instance, "fmi3SetClock");
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance,
                                               fmi3ValueReference valueReference,
                                               size_t *nDependencies)
{
    (void)valueReference, (void)nDependencies;
    return unsupported(instance, "fmi3GetNumberOfVariableDependencies");
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[], size_t nDependencies)
{
    (void)dependent, (void)elementIndicesOfDependent, (void)independents,
        (void)elementIndicesOfIndependents, (void)dependencyKinds, (void)nDependencies;
    return unsupported(instance, "fmi3GetVariableDependencies");
}

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    (void)FMUState;
    return unsupported(instance, "fmi3GetFMUState");
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    (void)FMUState;
    return unsupported(instance, "fmi3SetFMUState");
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    (void)FMUState;
    return unsupported(instance, "fmi3FreeFMUState");
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t *size)
{
    (void)FMUState, (void)size;
    return unsupported(instance, "fmi3SerializedFMUStateSize");
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                 fmi3Byte serializedState[], size_t size)
{
    (void)FMUState, (void)serializedState, (void)size;
    return unsupported(instance, "fmi3SerializeFMUState");
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                   size_t size, fmi3FMUState *FMUState)
{
    (void)serializedState, (void)size, (void)FMUState;
    return unsupported(instance, "fmi3DeserializeFMUState");
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                        size_t nUnknowns, const fmi3ValueReference knowns[],
                                        size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                        fmi3Float64 sensitivity[], size_t nSensitivity)
{
    (void)unknowns, (void)nUnknowns, (void)knowns, (void)nKnowns, (void)seed, (void)nSeed,
        (void)sensitivity, (void)nSensitivity;
    return unsupported(instance, "fmi3GetDirectionalDerivative");
}

fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                    size_t nUnknowns, const fmi3ValueReference knowns[],
                                    size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                    fmi3Float64 sensitivity[], size_t nSensitivity)
{
    (void)unknowns, (void)nUnknowns, (void)knowns, (void)nKnowns, (void)seed, (void)nSeed,
        (void)sensitivity, (void)nSensitivity;
    return unsupported(instance, "fmi3GetAdjointDerivative");
}

fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterConfigurationMode");
}

fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3ExitConfigurationMode");
}

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[])
{
    (void)valueReferences, (void)nValueReferences, (void)intervals, (void)qualifiers;
    return unsupported(instance, "fmi3GetIntervalDecimal");
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, fmi3UInt64 counters[],
                                   fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions,
        (void)qualifiers;
    return unsupported(instance, "fmi3GetIntervalFraction");
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, fmi3Float64 shifts[])
{
    (void)valueReferences, (void)nValueReferences, (void)shifts;
    return unsupported(instance, "fmi3GetShiftDecimal");
}

fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, fmi3UInt64 counters[],
                                fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return unsupported(instance, "fmi3GetShiftFraction");
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, const fmi3Float64 intervals[])
{
    (void)valueReferences, (void)nValueReferences, (void)intervals;
    return unsupported(instance, "fmi3SetIntervalDecimal");
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, const fmi3UInt64 counters[],
                                   const fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return unsupported(instance, "fmi3SetIntervalFraction");
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, const fmi3Float64 shifts[])
{
    (void)valueReferences, (void)nValueReferences, (void)shifts;
    return unsupported(instance, "fmi3SetShiftDecimal");
}

fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, const fmi3UInt64 counters[],
                                const fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return unsupported(instance, "fmi3SetShiftFraction");
}

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EvaluateDiscreteStates");
}

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterContinuousTimeMode");
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode,
                                       fmi3Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint, (void)enterEventMode, (void)terminateSimulation;
    return unsupported(instance, "fmi3CompletedIntegratorStep");
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{
    (void)time;
    return unsupported(instance, "fmi3SetTime");
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    (void)continuousStates, (void)nContinuousStates;
    return unsupported(instance, "fmi3SetContinuousStates");
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
    (void)derivatives, (void)nContinuousStates;
    return unsupported(instance, "fmi3GetContinuousStateDerivatives");
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[],
                                  size_t nEventIndicators)
{
    (void)eventIndicators, (void)nEventIndicators;
    return unsupported(instance, "fmi3GetEventIndicators");
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    (void)continuousStates, (void)nContinuousStates;
    return unsupported(instance, "fmi3GetContinuousStates");
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[],
                                             size_t nContinuousStates)
{
    (void)nominals, (void)nContinuousStates;
    return unsupported(instance, "fmi3GetNominalsOfContinuousStates");
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators)
{
    (void)nEventIndicators;
    return unsupported(instance, "fmi3GetNumberOfEventIndicators");
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates)
{
    (void)nContinuousStates;
    return unsupported(instance, "fmi3GetNumberOfContinuousStates");
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int32 orders[],
                                    fmi3Float64 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)orders, (void)values, (void)nValues;
    return unsupported(instance, "fmi3GetOutputDerivatives");
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    (void)clockReference, (void)activationTime;
    return unsupported(instance, "fmi3ActivateModelPartition");
}
