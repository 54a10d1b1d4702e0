/* The FMI 3.0 functions an exported system declines: other interfaces than Co-Simulation,
 * types it has no variables of, clocks, configuration mode, dependencies and derivatives. Each
 * logs why and returns fmi3Error (an instantiation: NULL). */
#include "fmi3_export.h"

#include <stddef.h>

static fmi3Instance decline_interface(fmi3InstanceEnvironment environment,
                                      fmi3LogMessageCallback log_message, const char *why)
{
    if (log_message != NULL) {
        log_message(environment, fmi3Error, "logStatusError", why);
    }
    return NULL;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)instanceName, (void)instantiationToken, (void)resourcePath, (void)visible,
        (void)loggingOn;
    return decline_interface(instanceEnvironment, logMessage,
                             "fmi3InstantiateModelExchange: this FMU is for Co-Simulation only");
}

fmi3Instance fmi3InstantiateScheduledExecution(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instanceName, (void)instantiationToken, (void)resourcePath, (void)visible,
        (void)loggingOn, (void)clockUpdate, (void)lockPreemption, (void)unlockPreemption;
    return decline_interface(
        instanceEnvironment, logMessage,
        "fmi3InstantiateScheduledExecution: this FMU is for Co-Simulation only");
}

fmi3Status fmi3GetFloat32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float32 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetFloat32: no variable of this FMU is a Float32");
}

fmi3Status fmi3GetInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                       size_t nValueReferences, fmi3Int8 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetInt8: no variable is an Int8");
}

fmi3Status fmi3GetUInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3UInt8 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetUInt8: no variable is a UInt8");
}

fmi3Status fmi3GetInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Int16 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetInt16: no variable is an Int16");
}

fmi3Status fmi3GetUInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3UInt16 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetUInt16: no variable is a UInt16");
}

fmi3Status fmi3GetUInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3UInt32 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetUInt32: no variable is a UInt32");
}

fmi3Status fmi3GetInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Int64 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetInt64: no variable is an Int64");
}

fmi3Status fmi3GetUInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3UInt64 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetUInt64: no variable is a UInt64");
}

fmi3Status fmi3GetString(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3String values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetString: no variable is a String");
}

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, size_t valueSizes[], fmi3Binary values[],
                         size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)valueSizes, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetBinary: no variable is a Binary");
}

fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Clock values[])
{
    (void)valueReferences, (void)nValueReferences, (void)values;
    return fmi3_refuse(instance, "fmi3GetClock: this FMU has no clocks");
}

fmi3Status fmi3SetFloat32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float32 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetFloat32: no variable of this FMU is a Float32");
}

fmi3Status fmi3SetInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                       size_t nValueReferences, const fmi3Int8 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetInt8: no variable is an Int8");
}

fmi3Status fmi3SetUInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3UInt8 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetUInt8: no variable is a UInt8");
}

fmi3Status fmi3SetInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Int16 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetInt16: no variable is an Int16");
}

fmi3Status fmi3SetUInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3UInt16 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetUInt16: no variable is a UInt16");
}

fmi3Status fmi3SetUInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3UInt32 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetUInt32: no variable is a UInt32");
}

fmi3Status fmi3SetInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Int64 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetInt64: no variable is an Int64");
}

fmi3Status fmi3SetUInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3UInt64 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetUInt64: no variable is a UInt64");
}

fmi3Status fmi3SetString(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3String values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetString: no variable is a String");
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)valueSizes, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3SetBinary: no variable is a Binary");
}

fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Clock values[])
{
    (void)valueReferences, (void)nValueReferences, (void)values;
    return fmi3_refuse(instance, "fmi3SetClock: this FMU has no clocks");
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance,
                                               fmi3ValueReference valueReference,
                                               size_t *nDependencies)
{
    (void)valueReference, (void)nDependencies;
    return fmi3_refuse(instance, "fmi3GetNumberOfVariableDependencies: dependencies are not "
                                 "provided: every output may depend on every input");
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[], size_t nDependencies)
{
    (void)dependent, (void)elementIndicesOfDependent, (void)independents,
        (void)elementIndicesOfIndependents, (void)dependencyKinds, (void)nDependencies;
    return fmi3_refuse(instance, "fmi3GetVariableDependencies: dependencies are not provided: "
                                 "every output may depend on every input");
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                        size_t nUnknowns, const fmi3ValueReference knowns[],
                                        size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                        fmi3Float64 sensitivity[], size_t nSensitivity)
{
    (void)unknowns, (void)nUnknowns, (void)knowns, (void)nKnowns, (void)seed, (void)nSeed,
        (void)sensitivity, (void)nSensitivity;
    return fmi3_refuse(instance, "fmi3GetDirectionalDerivative: derivatives are not provided");
}

fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                    size_t nUnknowns, const fmi3ValueReference knowns[],
                                    size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                    fmi3Float64 sensitivity[], size_t nSensitivity)
{
    (void)unknowns, (void)nUnknowns, (void)knowns, (void)nKnowns, (void)seed, (void)nSeed,
        (void)sensitivity, (void)nSensitivity;
    return fmi3_refuse(instance, "fmi3GetAdjointDerivative: derivatives are not provided");
}

fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{
    return fmi3_refuse(instance,
                       "fmi3EnterConfigurationMode: this FMU has no structural parameters");
}

fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{
    return fmi3_refuse(instance,
                       "fmi3ExitConfigurationMode: this FMU has no structural parameters");
}

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[])
{
    (void)valueReferences, (void)nValueReferences, (void)intervals, (void)qualifiers;
    return fmi3_refuse(instance, "fmi3GetIntervalDecimal: this FMU has no clocks");
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, fmi3UInt64 counters[],
                                   fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions,
        (void)qualifiers;
    return fmi3_refuse(instance, "fmi3GetIntervalFraction: this FMU has no clocks");
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, fmi3Float64 shifts[])
{
    (void)valueReferences, (void)nValueReferences, (void)shifts;
    return fmi3_refuse(instance, "fmi3GetShiftDecimal: this FMU has no clocks");
}

fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, fmi3UInt64 counters[],
                                fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return fmi3_refuse(instance, "fmi3GetShiftFraction: this FMU has no clocks");
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, const fmi3Float64 intervals[])
{
    (void)valueReferences, (void)nValueReferences, (void)intervals;
    return fmi3_refuse(instance, "fmi3SetIntervalDecimal: this FMU has no clocks");
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, const fmi3UInt64 counters[],
                                   const fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return fmi3_refuse(instance, "fmi3SetIntervalFraction: this FMU has no clocks");
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, const fmi3Float64 shifts[])
{
    (void)valueReferences, (void)nValueReferences, (void)shifts;
    return fmi3_refuse(instance, "fmi3SetShiftDecimal: this FMU has no clocks");
}

fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, const fmi3UInt64 counters[],
                                const fmi3UInt64 resolutions[])
{
    (void)valueReferences, (void)nValueReferences, (void)counters, (void)resolutions;
    return fmi3_refuse(instance, "fmi3SetShiftFraction: this FMU has no clocks");
}

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{
    return fmi3_refuse(instance, "fmi3EvaluateDiscreteStates: this FMU has no clocks");
}

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{
    return fmi3_refuse(instance, "fmi3EnterContinuousTimeMode: this FMU is for Co-Simulation only");
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode,
                                       fmi3Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint, (void)enterEventMode, (void)terminateSimulation;
    return fmi3_refuse(instance, "fmi3CompletedIntegratorStep: this FMU is for Co-Simulation only");
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{
    (void)time;
    return fmi3_refuse(instance, "fmi3SetTime: this FMU is for Co-Simulation only");
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    (void)continuousStates, (void)nContinuousStates;
    return fmi3_refuse(instance, "fmi3SetContinuousStates: this FMU is for Co-Simulation only");
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
    (void)derivatives, (void)nContinuousStates;
    return fmi3_refuse(instance, "fmi3GetContinuousStateDerivatives: derivatives are not provided");
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[],
                                  size_t nEventIndicators)
{
    (void)eventIndicators, (void)nEventIndicators;
    return fmi3_refuse(instance, "fmi3GetEventIndicators: this FMU is for Co-Simulation only");
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    (void)continuousStates, (void)nContinuousStates;
    return fmi3_refuse(instance, "fmi3GetContinuousStates: this FMU is for Co-Simulation only");
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[],
                                             size_t nContinuousStates)
{
    (void)nominals, (void)nContinuousStates;
    return fmi3_refuse(instance,
                       "fmi3GetNominalsOfContinuousStates: this FMU is for Co-Simulation only");
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators)
{
    (void)nEventIndicators;
    return fmi3_refuse(instance,
                       "fmi3GetNumberOfEventIndicators: this FMU is for Co-Simulation only");
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates)
{
    (void)nContinuousStates;
    return fmi3_refuse(instance,
                       "fmi3GetNumberOfContinuousStates: this FMU is for Co-Simulation only");
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int32 orders[],
                                    fmi3Float64 values[], size_t nValues)
{
    (void)valueReferences, (void)nValueReferences, (void)orders, (void)values, (void)nValues;
    return fmi3_refuse(instance, "fmi3GetOutputDerivatives: derivatives are not provided");
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    (void)clockReference, (void)activationTime;
    return fmi3_refuse(instance, "fmi3ActivateModelPartition: this FMU is for Co-Simulation only");
}
