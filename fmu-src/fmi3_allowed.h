/* When each FMI 3.0 function may be called: the modes it is allowed in, one row per
 * function (the modes and their sets are in fmi3_instance.h), and the entry macro that names a
 * function once. */
#ifndef SYSSIMX_FMI3_ALLOWED_H
#define SYSSIMX_FMI3_ALLOWED_H

#include "fmi3_instance.h"

/* The function's name and the modes it is allowed in: the two arguments of the check
 * at the top of each entry point, e.g. fmi3_checked(instance, FMI3_CALL(fmi3DoStep)). */
#define FMI3_CALL(name) #name, FMI3_ALLOWED_##name

#define FMI3_ALLOWED_fmi3CompletedIntegratorStep       MODE_BIT(MODE_CONTINUOUS_TIME)
#define FMI3_ALLOWED_fmi3DeserializeFMUState           MODES_ANY
#define FMI3_ALLOWED_fmi3DoStep                        MODE_BIT(MODE_STEP)
#define FMI3_ALLOWED_fmi3EnterContinuousTimeMode       MODE_BIT(MODE_EVENT)
#define FMI3_ALLOWED_fmi3EnterEventMode                MODE_BIT(MODE_STEP) | MODES_EVENT_OR_CONTINUOUS
#define FMI3_ALLOWED_fmi3EnterInitializationMode       MODE_BIT(MODE_INSTANTIATED)
#define FMI3_ALLOWED_fmi3EnterStepMode                 MODE_BIT(MODE_EVENT)
#define FMI3_ALLOWED_fmi3GetIntervalDecimal            MODE_BIT(MODE_INITIALIZATION) | MODE_BIT(MODE_EVENT)
#define FMI3_ALLOWED_fmi3GetShiftDecimal               MODE_BIT(MODE_INITIALIZATION) | MODE_BIT(MODE_EVENT)
#define FMI3_ALLOWED_fmi3ExitInitializationMode        MODE_BIT(MODE_INITIALIZATION)
#define FMI3_ALLOWED_fmi3FreeFMUState                  MODES_ANY
#define FMI3_ALLOWED_fmi3GetBinary                     MODES_GET
#define FMI3_ALLOWED_fmi3GetBoolean                    MODES_GET
#define FMI3_ALLOWED_fmi3GetClock                      MODES_GET
#define FMI3_ALLOWED_fmi3GetContinuousStateDerivatives MODES_MODEL_EVALUATION
#define FMI3_ALLOWED_fmi3GetContinuousStates           MODES_MODEL_EVALUATION
#define FMI3_ALLOWED_fmi3GetDirectionalDerivative      MODES_GET
#define FMI3_ALLOWED_fmi3GetEventIndicators            MODES_MODEL_EVALUATION
#define FMI3_ALLOWED_fmi3GetFMUState                   MODES_ANY
#define FMI3_ALLOWED_fmi3GetFloat32                    MODES_GET
#define FMI3_ALLOWED_fmi3GetFloat64                    MODES_GET
#define FMI3_ALLOWED_fmi3GetInt16                      MODES_GET
#define FMI3_ALLOWED_fmi3GetInt32                      MODES_GET
#define FMI3_ALLOWED_fmi3GetInt64                      MODES_GET
#define FMI3_ALLOWED_fmi3GetInt8                       MODES_GET
#define FMI3_ALLOWED_fmi3GetNominalsOfContinuousStates MODE_BIT(MODE_INSTANTIATED) | MODES_EVENT_OR_CONTINUOUS | MODE_BIT(MODE_TERMINATED)
#define FMI3_ALLOWED_fmi3GetNumberOfContinuousStates   MODES_ANY
#define FMI3_ALLOWED_fmi3GetNumberOfEventIndicators    MODES_ANY
#define FMI3_ALLOWED_fmi3GetString                     MODES_GET
#define FMI3_ALLOWED_fmi3GetUInt16                     MODES_GET
#define FMI3_ALLOWED_fmi3GetUInt32                     MODES_GET
#define FMI3_ALLOWED_fmi3GetUInt64                     MODES_GET
#define FMI3_ALLOWED_fmi3GetUInt8                      MODES_GET
#define FMI3_ALLOWED_fmi3Reset                         MODES_ANY
#define FMI3_ALLOWED_fmi3SerializeFMUState             MODES_ANY
#define FMI3_ALLOWED_fmi3SerializedFMUStateSize        MODES_ANY
#define FMI3_ALLOWED_fmi3SetBinary                     MODES_SET
#define FMI3_ALLOWED_fmi3SetBoolean                    MODES_SET
#define FMI3_ALLOWED_fmi3SetClock                      MODES_SET
#define FMI3_ALLOWED_fmi3SetContinuousStates           MODE_BIT(MODE_CONTINUOUS_TIME)
#define FMI3_ALLOWED_fmi3SetDebugLogging               MODES_ANY
#define FMI3_ALLOWED_fmi3SetFMUState                   MODES_ANY
#define FMI3_ALLOWED_fmi3SetFloat32                    MODES_SET
#define FMI3_ALLOWED_fmi3SetFloat64                    MODES_SET
#define FMI3_ALLOWED_fmi3SetInt16                      MODES_SET
#define FMI3_ALLOWED_fmi3SetInt32                      MODES_SET
#define FMI3_ALLOWED_fmi3SetInt64                      MODES_SET
#define FMI3_ALLOWED_fmi3SetInt8                       MODES_SET
#define FMI3_ALLOWED_fmi3SetString                     MODES_SET
#define FMI3_ALLOWED_fmi3SetTime                       MODES_EVENT_OR_CONTINUOUS
#define FMI3_ALLOWED_fmi3SetUInt16                     MODES_SET
#define FMI3_ALLOWED_fmi3SetUInt32                     MODES_SET
#define FMI3_ALLOWED_fmi3SetUInt64                     MODES_SET
#define FMI3_ALLOWED_fmi3SetUInt8                      MODES_SET
#define FMI3_ALLOWED_fmi3Terminate                     MODES_INITIALIZED
#define FMI3_ALLOWED_fmi3UpdateDiscreteStates          MODE_BIT(MODE_EVENT)

#endif
