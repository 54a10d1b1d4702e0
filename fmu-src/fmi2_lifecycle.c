/* Creating, setting up, initializing, resetting and freeing an instance. */
#include <string.h>

#include "fmi2_allowed.h"
#include "fmu_guid.h"
#include "fmu_instance.h"
#include "fmu_log.h"

const char *fmi2GetTypesPlatform(void)
{
    return fmi2TypesPlatform;
}

const char *fmi2GetVersion(void)
{
    return fmi2Version;
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2SetDebugLogging));
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_set_logging(inst, "fmi2SetDebugLogging", loggingOn != fmi2False,
                                       nCategories, categories));
}

/* Hands the core's message to the importer's FMI 2.0 logger. The message holds no printf
 * conversion (fmu_log.c), so it is the format itself. */
static void forward_log(const fmu_logging_callbacks *callbacks, const char *instance_name,
                        fmu_status status, const char *category, const char *message)
{
    fmi2CallbackLogger logger = (fmi2CallbackLogger)callbacks->logger;
    logger(callbacks->environment, instance_name, fmi2_status(status), category, message);
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    (void)fmuResourceLocation; /* the models need no resources */
    (void)visible;
    if (functions == NULL)
        return NULL;
    /* A stand-in to report failures before the instance exists. */
    fmu_instance reporter = {
        .name = (char *)(instanceName ? instanceName : "(unnamed)"),
        .callbacks = {forward_log, (void (*)(void))functions->logger,
                      functions->componentEnvironment},
        .logging_on = loggingOn != fmi2False,
        .log_categories = LOG_ALL_CATEGORIES,
    };
    if (instanceName == NULL || instanceName[0] == '\0') {
        fmu_error(&reporter, "fmi2Instantiate: the instance name is missing");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation && fmuType != fmi2ModelExchange) {
        fmu_error(&reporter,
                  "fmi2Instantiate: fmuType %d is neither fmi2ModelExchange (%d) nor "
                  "fmi2CoSimulation (%d)",
                  (int)fmuType, (int)fmi2ModelExchange, (int)fmi2CoSimulation);
        return NULL;
    }
    char guid[FMU_GUID_LENGTH];
    fmu_guid(guid);
    if (fmuGUID == NULL || strcmp(fmuGUID, guid) != 0) {
        fmu_error(&reporter, "fmi2Instantiate: GUID %s does not match this FMU's GUID %s",
                  fmuGUID ? fmuGUID : "(null)", guid);
        return NULL;
    }

    fmu_instance *inst = fmu_instance_create(&reporter, sizeof(fmu_instance), "fmi2Instantiate");
    /* Model Exchange starts in event mode: the importer handles the initial events */
    if (inst != NULL && fmuType == fmi2ModelExchange)
        inst->running_phase = PHASE_EVENT;
    return inst;
}

void fmi2FreeInstance(fmi2Component c)
{
    fmu_instance *inst = c;
    /* FMI 2.0 forbids even this call after fmi2Fatal; saying so lets a master's tests see it */
    if (inst != NULL && inst->phase == PHASE_FATAL)
        fmu_refuse_in_phase(inst, "fmi2FreeInstance");
    fmu_instance_free(inst);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2SetupExperiment));
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_setup_experiment(inst, "fmi2SetupExperiment",
                                            toleranceDefined != fmi2False, tolerance, startTime,
                                            stopTimeDefined != fmi2False, stopTime));
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    fmu_instance *inst =
        fmu_checked(c, FMI2_CALL(fmi2EnterInitializationMode));
    if (inst == NULL)
        return fmi2Error;
    inst->phase = PHASE_INITIALIZATION;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    fmu_instance *inst =
        fmu_checked(c, FMI2_CALL(fmi2ExitInitializationMode));
    if (inst == NULL)
        return fmi2Error;
    fmu_exit_initialization(inst);
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2Terminate));
    if (inst == NULL)
        return fmi2Error;
    inst->phase = PHASE_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2Reset));
    if (inst == NULL)
        return fmi2Error;
    fmu_reset(inst);
    return fmi2OK;
}
