/* When each FMI 2.0 function may be called: the phases it is allowed in, one row per
 * function (the phases and their sets are in fmu_instance.h), and the entry macro that names a
 * function once. */
#ifndef SYSSIMX_FMI2_ALLOWED_H
#define SYSSIMX_FMI2_ALLOWED_H

#include "fmi2_status.h"
#include "fmu_instance.h"

/* The function's name and the phases it is allowed in: the two arguments of the check
 * at the top of each entry point, e.g. fmu_checked(c, FMI2_CALL(fmi2DoStep)). */
#define FMI2_CALL(name) #name, FMI2_ALLOWED_##name

#define FMI2_ALLOWED_fmi2CancelStep                    PHASE_BIT(PHASE_STEP)
#define FMI2_ALLOWED_fmi2CompletedIntegratorStep       PHASE_BIT(PHASE_CONTINUOUS_TIME)
#define FMI2_ALLOWED_fmi2DeSerializeFMUstate           PHASES_ANY
#define FMI2_ALLOWED_fmi2DoStep                        PHASE_BIT(PHASE_STEP)
#define FMI2_ALLOWED_fmi2EnterContinuousTimeMode       PHASE_BIT(PHASE_EVENT)
#define FMI2_ALLOWED_fmi2EnterEventMode                PHASES_EVENT_OR_CONTINUOUS
#define FMI2_ALLOWED_fmi2EnterInitializationMode       PHASE_BIT(PHASE_INSTANTIATED)
#define FMI2_ALLOWED_fmi2ExitInitializationMode        PHASE_BIT(PHASE_INITIALIZATION)
#define FMI2_ALLOWED_fmi2FreeFMUstate                  PHASES_ANY
#define FMI2_ALLOWED_fmi2GetBoolean                    PHASES_ANY
#define FMI2_ALLOWED_fmi2GetBooleanStatus              PHASES_STATUS
#define FMI2_ALLOWED_fmi2GetContinuousStates           PHASES_MODEL_EVALUATION
#define FMI2_ALLOWED_fmi2GetDerivatives                PHASES_MODEL_EVALUATION
#define FMI2_ALLOWED_fmi2GetDirectionalDerivative      PHASES_INITIALIZED
#define FMI2_ALLOWED_fmi2GetEventIndicators            PHASES_MODEL_EVALUATION
#define FMI2_ALLOWED_fmi2GetFMUstate                   PHASES_ANY
#define FMI2_ALLOWED_fmi2GetInteger                    PHASES_ANY
#define FMI2_ALLOWED_fmi2GetIntegerStatus              PHASES_STATUS
#define FMI2_ALLOWED_fmi2GetNominalsOfContinuousStates PHASES_NOMINALS
#define FMI2_ALLOWED_fmi2GetReal                       PHASES_ANY
#define FMI2_ALLOWED_fmi2GetRealStatus                 PHASES_STATUS
#define FMI2_ALLOWED_fmi2GetStatus                     PHASES_STATUS
#define FMI2_ALLOWED_fmi2GetString                     PHASES_ANY
#define FMI2_ALLOWED_fmi2GetStringStatus               PHASES_STATUS
#define FMI2_ALLOWED_fmi2NewDiscreteStates             PHASE_BIT(PHASE_EVENT)
#define FMI2_ALLOWED_fmi2Reset                         PHASES_ANY
#define FMI2_ALLOWED_fmi2SerializeFMUstate             PHASES_ANY
#define FMI2_ALLOWED_fmi2SerializedFMUstateSize        PHASES_ANY
#define FMI2_ALLOWED_fmi2SetBoolean                    PHASES_SETTABLE
#define FMI2_ALLOWED_fmi2SetContinuousStates           PHASE_BIT(PHASE_CONTINUOUS_TIME)
#define FMI2_ALLOWED_fmi2SetDebugLogging               PHASES_ANY
#define FMI2_ALLOWED_fmi2SetFMUstate                   PHASES_ANY
#define FMI2_ALLOWED_fmi2SetInteger                    PHASES_SETTABLE
#define FMI2_ALLOWED_fmi2SetReal                       PHASES_SETTABLE
#define FMI2_ALLOWED_fmi2SetString                     PHASES_SETTABLE
#define FMI2_ALLOWED_fmi2SetTime                       PHASES_EVENT_OR_CONTINUOUS
#define FMI2_ALLOWED_fmi2SetupExperiment               PHASE_BIT(PHASE_INSTANTIATED)
#define FMI2_ALLOWED_fmi2Terminate                     PHASES_INITIALIZED

#endif
