/* Creating, setting up, initializing, resetting and freeing an instance. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_guid.h"
#include "fmu_instance.h"
#include "fmu_log.h"
#include "fmu_solver.h"

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
    fmu_instance *inst = fmu_checked(c, "fmi2SetDebugLogging", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    unsigned selected = 0;
    for (size_t i = 0; i < nCategories; ++i) {
        int category = fmu_log_category_from_name(categories ? categories[i] : NULL);
        if (category < 0)
            return fmu_error(inst, "fmi2SetDebugLogging: unknown log category \"%s\"",
                             categories && categories[i] ? categories[i] : "(null)");
        selected |= 1u << category;
    }
    inst->logging_on = loggingOn != fmi2False;
    inst->log_categories = nCategories > 0 ? selected : LOG_ALL_CATEGORIES;
    return fmi2OK;
}

static void free_instance(fmu_instance *inst)
{
    if (inst == NULL)
        return;
    fmu_solver_free(inst);
    free(inst->values);
    free(inst->x);
    free(inst->dx);
    free(inst->z_before);
    free(inst->z_after);
    free(inst->fired);
    free(inst->z_previous);
    free(inst->name);
    free(inst);
}

static int allocate_arrays(fmu_instance *inst)
{
    size_t n_states = inst->model->n_states;
    size_t n_indicators = inst->model->n_event_indicators;
    /* calloc(0) may return NULL: allocate at least one element so NULL always means failure */
    inst->values = calloc(inst->n_variables + 1, sizeof(double));
    inst->x = calloc(n_states + 1, sizeof(double));
    inst->dx = calloc(n_states + 1, sizeof(double));
    inst->z_before = calloc(n_indicators + 1, sizeof(double));
    inst->z_after = calloc(n_indicators + 1, sizeof(double));
    inst->fired = calloc(n_indicators + 1, sizeof(int));
    inst->z_previous = calloc(n_indicators + 1, sizeof(double));
    return inst->values && inst->x && inst->dx && inst->z_before && inst->z_after && inst->fired &&
           inst->z_previous;
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
        .callbacks = {functions->logger, functions->componentEnvironment},
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

    fmu_instance *inst = calloc(1, sizeof *inst);
    if (inst == NULL) {
        fmu_error(&reporter, "fmi2Instantiate: out of memory");
        return NULL;
    }
    inst->callbacks = reporter.callbacks;
    inst->logging_on = reporter.logging_on;
    inst->log_categories = LOG_ALL_CATEGORIES;
    inst->model = &fmu_model;
    inst->solver_variables = fmu_solver_variables;
    inst->n_variables = fmu_model.n_variables + fmu_solver_variable_count;
    inst->phase = PHASE_INSTANTIATED;
    /* Model Exchange starts in event mode: the importer handles the initial events */
    inst->running_phase = fmuType == fmi2ModelExchange ? PHASE_EVENT : PHASE_STEP;
    inst->name = malloc(strlen(instanceName) + 1);
    if (inst->name == NULL || !allocate_arrays(inst)) {
        fmu_error(&reporter, "fmi2Instantiate: out of memory");
        free_instance(inst);
        return NULL;
    }
    strcpy(inst->name, instanceName);
    memcpy(inst->guid, guid, sizeof guid);
    fmu_apply_start_values(inst);
    if (fmu_solver_create(inst) != 0) {
        fmu_error(&reporter, "fmi2Instantiate: the %s solver could not be created",
                  fmu_solver_name);
        free_instance(inst);
        return NULL;
    }
    return inst;
}

void fmi2FreeInstance(fmi2Component c)
{
    fmu_instance *inst = c;
    /* FMI 2.0 forbids even this call after fmi2Fatal; saying so lets a master's tests see it */
    if (inst != NULL && inst->phase == PHASE_FATAL)
        fmu_refuse_in_phase(inst, "fmi2FreeInstance");
    free_instance(inst);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    fmu_instance *inst = fmu_checked(c, "fmi2SetupExperiment", PHASE_BIT(PHASE_INSTANTIATED));
    if (inst == NULL)
        return fmi2Error;
    if (!isfinite(startTime))
        return fmu_error(inst, "fmi2SetupExperiment: the start time is not finite");
    if (toleranceDefined && !(tolerance > 0.0 && tolerance < 1.0))
        return fmu_error(inst, "fmi2SetupExperiment: tolerance %g is not in (0, 1)", tolerance);
    if (stopTimeDefined && !(stopTime >= startTime))
        return fmu_error(inst, "fmi2SetupExperiment: stop time %g is before start time %g",
                         stopTime, startTime);
    inst->tolerance_defined = toleranceDefined != fmi2False;
    inst->tolerance = toleranceDefined ? tolerance : 0.0;
    inst->time = startTime;
    inst->outputs_stale = 1;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    fmu_instance *inst =
        fmu_checked(c, "fmi2EnterInitializationMode", PHASE_BIT(PHASE_INSTANTIATED));
    if (inst == NULL)
        return fmi2Error;
    inst->phase = PHASE_INITIALIZATION;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    fmu_instance *inst =
        fmu_checked(c, "fmi2ExitInitializationMode", PHASE_BIT(PHASE_INITIALIZATION));
    if (inst == NULL)
        return fmi2Error;
    fmu_refresh_outputs(inst); /* states from the final start values */
    inst->phase = inst->running_phase;
    fmu_refresh_outputs(inst);
    fmu_solver_invalidate(inst);
    /* Model Exchange: the first event mode compares the indicators with their initial values */
    fmu_event_indicators(inst, inst->z_previous);
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    fmu_instance *inst = fmu_checked(c, "fmi2Terminate", PHASES_INITIALIZED);
    if (inst == NULL)
        return fmi2Error;
    inst->phase = PHASE_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    fmu_instance *inst = fmu_checked(c, "fmi2Reset", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    inst->phase = PHASE_INSTANTIATED;
    fmu_apply_start_values(inst);
    fmu_solver_invalidate(inst);
    return fmi2OK;
}
