/* The FMI 2.0 Co-Simulation entry points of an exported system (exported_system.h). The
 * instance is the state machine of the standard; the system does the work. */
#include "exported_system.h"

#include "fmi2Functions.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum {
    MODE_INSTANTIATED,
    MODE_INITIALIZATION,
    MODE_STEPPING,
    MODE_TERMINATED,
    MODE_ERROR
} fmi2_mode;

typedef struct {
    exported_system *system;
    fmi2CallbackFunctions callbacks;
    char *name;
    int logging_on;
    fmi2_mode mode;
    double start_time;
    double last_successful_time;
    int terminated_by_member;
} fmi2_instance;

static void log_to_importer(void *user, int error, const char *message)
{
    fmi2_instance *instance = user;
    if (instance->callbacks.logger != NULL && (error || instance->logging_on)) {
        /* the message is an argument, never a format: a member's message may hold '%' */
        instance->callbacks.logger(instance->callbacks.componentEnvironment, instance->name,
                                   error ? fmi2Error : fmi2OK, error ? "logStatusError" : "logAll",
                                   "%s", message);
    }
}

static fmi2Status refuse(fmi2_instance *instance, const char *what)
{
    log_to_importer(instance, 1, what);
    return fmi2Error;
}

/* file:///path or file:/path (RFC 8089), percent-escapes decoded; NULL if not a file URI */
static char *uri_path(const char *uri)
{
    if (uri == NULL || strncmp(uri, "file:", 5) != 0) {
        return NULL;
    }
    const char *path = uri + 5;
    if (strncmp(path, "///", 3) == 0) {
        path += 2;
    } else if (strncmp(path, "//localhost/", 12) == 0) {
        path += 11;
    }
    char *decoded = malloc(strlen(path) + 1);
    if (decoded == NULL) {
        return NULL;
    }
    size_t at = 0;
    for (const char *c = path; *c; c++) {
        unsigned int byte;
        if (c[0] == '%' && c[1] && c[2] && sscanf(c + 1, "%2x", &byte) == 1) {
            decoded[at++] = (char)byte;
            c += 2;
        } else {
            decoded[at++] = *c;
        }
    }
    while (at > 1 && decoded[at - 1] == '/') {
        at--;
    }
    decoded[at] = '\0';
    return decoded;
}

const char *fmi2GetTypesPlatform(void)
{
    return fmi2TypesPlatform;
}

const char *fmi2GetVersion(void)
{
    return fmi2Version;
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    (void)visible;
    if (functions == NULL || instanceName == NULL) {
        return NULL;
    }
    fmi2_instance *instance = calloc(1, sizeof *instance);
    char *resources = uri_path(fmuResourceLocation);
    if (instance != NULL) {
        instance->callbacks = *functions;
        instance->logging_on = loggingOn;
        instance->name = malloc(strlen(instanceName) + 1);
    }
    if (instance == NULL || instance->name == NULL) {
        free(resources);
        free(instance);
        return NULL;
    }
    strcpy(instance->name, instanceName);
    if (fmuType != fmi2CoSimulation || resources == NULL) {
        log_to_importer(instance, 1,
                        fmuType != fmi2CoSimulation
                            ? "fmi2Instantiate: this FMU is for Co-Simulation only"
                            : "fmi2Instantiate: the resource location is no file: URI");
    } else {
        instance->system = exported_system_new(resources, fmuGUID, log_to_importer, instance);
    }
    free(resources);
    if (instance->system == NULL) {
        free(instance->name);
        free(instance);
        return NULL;
    }
    return instance;
}

void fmi2FreeInstance(fmi2Component c)
{
    fmi2_instance *instance = c;
    if (instance != NULL) {
        exported_system_free(instance->system);
        free(instance->name);
        free(instance);
    }
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    (void)nCategories, (void)categories;
    fmi2_instance *instance = c;
    if (instance == NULL) {
        return fmi2Error;
    }
    instance->logging_on = loggingOn;
    return fmi2OK;
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    /* the members keep the tolerances the system was exported with */
    (void)toleranceDefined, (void)tolerance, (void)stopTimeDefined, (void)stopTime;
    fmi2_instance *instance = c;
    if (instance == NULL) {
        return fmi2Error;
    }
    if (instance->mode != MODE_INSTANTIATED) {
        return refuse(instance, "fmi2SetupExperiment: only before initialization mode");
    }
    instance->start_time = startTime;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    fmi2_instance *instance = c;
    if (instance == NULL) {
        return fmi2Error;
    }
    if (instance->mode != MODE_INSTANTIATED) {
        return refuse(instance, "fmi2EnterInitializationMode: only once, after instantiation");
    }
    if (exported_system_start(instance->system, instance->start_time) != 0) {
        instance->mode = MODE_ERROR;
        return fmi2Error;
    }
    instance->mode = MODE_INITIALIZATION;
    instance->last_successful_time = instance->start_time;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    fmi2_instance *instance = c;
    if (instance == NULL) {
        return fmi2Error;
    }
    if (instance->mode != MODE_INITIALIZATION) {
        return refuse(instance, "fmi2ExitInitializationMode: not in initialization mode");
    }
    exported_system_steps(instance->system);
    instance->mode = MODE_STEPPING;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    fmi2_instance *instance = c;
    if (instance == NULL) {
        return fmi2Error;
    }
    instance->mode = MODE_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    fmi2_instance *instance = c;
    if (instance == NULL) {
        return fmi2Error;
    }
    exported_system_reset(instance->system);
    instance->mode = MODE_INSTANTIATED;
    instance->start_time = 0.0;
    instance->terminated_by_member = 0;
    return fmi2OK;
}

static fmi2Status from(int result)
{
    return result == 0 ? fmi2OK : fmi2Error;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    fmi2_instance *instance = c;
    if (instance == NULL || (nvr > 0 && (vr == NULL || value == NULL))) {
        return fmi2Error;
    }
    return from(exported_system_get_real(instance->system, vr, nvr, value));
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[])
{
    fmi2_instance *instance = c;
    if (instance == NULL || (nvr > 0 && (vr == NULL || value == NULL))) {
        return fmi2Error;
    }
    return from(exported_system_get_integer(instance->system, vr, nvr, value, 0));
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{
    fmi2_instance *instance = c;
    if (instance == NULL || (nvr > 0 && (vr == NULL || value == NULL))) {
        return fmi2Error;
    }
    return from(exported_system_set_real(instance->system, vr, nvr, value));
}

static fmi2Status no_variables(fmi2Component c, size_t nvr, const char *function)
{
    fmi2_instance *instance = c;
    if (instance == NULL) {
        return fmi2Error;
    }
    if (nvr == 0) {
        return fmi2OK;
    }
    char message[128];
    snprintf(message, sizeof message, "%s: this FMU has no variables of that type", function);
    return refuse(instance, message);
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{
    fmi2_instance *instance = c;
    if (instance == NULL || (nvr > 0 && (vr == NULL || value == NULL))) {
        return fmi2Error;
    }
    return from(exported_system_set_integer(instance->system, vr, nvr, value, 0));
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[])
{
    fmi2_instance *instance = c;
    if (instance == NULL || (nvr > 0 && (vr == NULL || value == NULL))) {
        return fmi2Error;
    }
    return from(exported_system_get_integer(instance->system, vr, nvr, value, 1));
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{
    fmi2_instance *instance = c;
    if (instance == NULL || (nvr > 0 && (vr == NULL || value == NULL))) {
        return fmi2Error;
    }
    return from(exported_system_set_integer(instance->system, vr, nvr, value, 1));
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[])
{
    (void)vr, (void)value;
    return no_variables(c, nvr, "fmi2GetString");
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[])
{
    (void)vr, (void)value;
    return no_variables(c, nvr, "fmi2SetString");
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmi2_instance *instance = c;
    if (instance == NULL || FMUstate == NULL) {
        return fmi2Error;
    }
    exported_state *state = exported_state_save(instance->system);
    if (state == NULL) {
        return fmi2Error;
    }
    /* a state handed in is replaced, as the standard lets the FMU reuse it */
    exported_state_free(*FMUstate);
    *FMUstate = state;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    fmi2_instance *instance = c;
    if (instance == NULL || FMUstate == NULL) {
        return fmi2Error;
    }
    if (exported_state_restore(instance->system, FMUstate) != 0) {
        return fmi2Error;
    }
    instance->last_successful_time = exported_system_time(instance->system);
    instance->terminated_by_member = 0;
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    if (c == NULL || FMUstate == NULL) {
        return fmi2Error;
    }
    exported_state_free(*FMUstate);
    *FMUstate = NULL;
    return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    fmi2_instance *instance = c;
    if (instance == NULL || FMUstate == NULL || size == NULL) {
        return fmi2Error;
    }
    unsigned char *bytes = exported_state_serialize(instance->system, FMUstate, size);
    free(bytes);
    return bytes != NULL ? fmi2OK : fmi2Error;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[],
                                 size_t size)
{
    fmi2_instance *instance = c;
    if (instance == NULL || FMUstate == NULL || serializedState == NULL) {
        return fmi2Error;
    }
    size_t needed = 0;
    unsigned char *bytes = exported_state_serialize(instance->system, FMUstate, &needed);
    if (bytes == NULL) {
        return fmi2Error;
    }
    fmi2Status status = fmi2OK;
    if (needed > size) {
        status = refuse(instance, "fmi2SerializeFMUstate: the buffer is smaller than "
                                  "fmi2SerializedFMUstateSize said");
    } else {
        memcpy(serializedState, bytes, needed);
    }
    free(bytes);
    return status;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate)
{
    fmi2_instance *instance = c;
    if (instance == NULL || serializedState == NULL || FMUstate == NULL) {
        return fmi2Error;
    }
    exported_state *state =
        exported_state_deserialize(instance->system, (const unsigned char *)serializedState, size);
    if (state == NULL) {
        return fmi2Error;
    }
    exported_state_free(*FMUstate);
    *FMUstate = state;
    return fmi2OK;
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    (void)vUnknown_ref, (void)nUnknown, (void)vKnown_ref, (void)nKnown, (void)dvKnown,
        (void)dvUnknown;
    return c != NULL ? refuse(c, "fmi2GetDirectionalDerivative: not provided") : fmi2Error;
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return c != NULL ? refuse(c, "fmi2SetRealInputDerivatives: inputs are held over a step")
                     : fmi2Error;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return c != NULL ? refuse(c, "fmi2GetRealOutputDerivatives: not provided") : fmi2Error;
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    fmi2_instance *instance = c;
    if (instance == NULL) {
        return fmi2Error;
    }
    if (instance->mode != MODE_STEPPING || instance->terminated_by_member) {
        return refuse(instance, instance->terminated_by_member
                                    ? "fmi2DoStep: a member ended the simulation"
                                    : "fmi2DoStep: not in step mode (initialize first)");
    }
    if (!(communicationStepSize > 0.0)) {
        return refuse(instance, "fmi2DoStep: the step size must be positive");
    }
    double reached;
    int returned_early;
    int result = exported_system_step(instance->system, currentCommunicationPoint,
                                      communicationStepSize, 0, &reached, &returned_early);
    instance->last_successful_time = reached;
    if (result == 1) {
        instance->terminated_by_member = 1;
        return fmi2Discard;
    }
    if (result != 0) {
        instance->mode = MODE_ERROR;
        return fmi2Error;
    }
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    return c != NULL ? refuse(c, "fmi2CancelStep: doStep never runs asynchronously") : fmi2Error;
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    fmi2_instance *instance = c;
    if (instance == NULL || value == NULL || s != fmi2DoStepStatus) {
        return fmi2Discard;
    }
    *value = instance->mode == MODE_ERROR ? fmi2Error : fmi2OK;
    return fmi2OK;
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    fmi2_instance *instance = c;
    if (instance == NULL || value == NULL || s != fmi2LastSuccessfulTime) {
        return fmi2Discard;
    }
    *value = instance->last_successful_time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    fmi2_instance *instance = c;
    if (instance == NULL || value == NULL || s != fmi2Terminated) {
        return fmi2Discard;
    }
    *value = instance->terminated_by_member ? fmi2True : fmi2False;
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)c, (void)s, (void)value;
    return fmi2Discard;
}
