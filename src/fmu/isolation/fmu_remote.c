/* The engine's side of an isolated FMU: fmi2 functions (or FMI 1.0 Co-Simulation ones) that
 * forward every call to the FMU host process (fmu_host.c) and turn the host's death or silence
 * into an fmi2Fatal that says why. */
#define _DEFAULT_SOURCE

#include "fmu_remote.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "channel.h"
#include "child_process.h"
#include "fmi1Functions.h"
#include "fmi2Functions.h"
#include "fmu_environment.h"
#include "fmu_remote_protocol.h"

struct ssx_remote {
    int pid; /* 0 while no host runs */
    int socket;
    double call_timeout;
    int fmi1;          /* the binary is FMI 1.0 Co-Simulation */
    uint64_t exported; /* bit i: the binary exports remote_call_names[i] (or the FMI 1.0 one) */
    char *host_path;
    char *binary_path;
    char *model_identifier;
    const void *handed; /* the live instance's environment, for the FMU's messages */
    char *instance_name;
    char *buffer; /* a request's payload, then each reply's */
    size_t capacity;
    /* The engine reads the same outputs after every doStep. The host reads them right after
     * the step and sends them with its result, so that fmi2GetReal costs no second round
     * trip; any other call in between discards them. */
    fmi2ValueReference *read_after_step;
    size_t n_read_after_step;
    double *read_values;
    int read_status;
    int read_ready;
    char gone[512]; /* why the host ended, "" while it runs */
    channel_watch watch; /* asked while a call waits: the engine's run stops it */
};

/* ------------------------------------------------------------------ the host process */

static int reserve(ssx_remote *r, size_t size)
{
    if (size <= r->capacity) {
        return 0;
    }
    char *bigger = realloc(r->buffer, size);
    if (bigger == NULL) {
        return -1;
    }
    r->buffer = bigger;
    r->capacity = size;
    return 0;
}

static void close_host(ssx_remote *r, char *how, size_t how_size)
{
    if (r->socket >= 0) {
        child_process_close_socket(r->socket);
        r->socket = -1;
    }
    if (r->pid > 0) {
        child_process_reap(r->pid, how, how_size);
        child_process_kill_group(r->pid); /* whatever the FMU forked is ended with it */
        r->pid = 0;
    }
}

/* The deadline of a call started now (CHANNEL_NO_DEADLINE without a call timeout). */
static double call_deadline(const ssx_remote *r)
{
    return channel_deadline_after(r->call_timeout);
}

/* Starts the host and reads its HELLO. */
static int start_host(ssx_remote *r, char *error, size_t error_size)
{
    char standard[] = REMOTE_STANDARD_FMI2;
    if (r->fmi1) {
        memcpy(standard, REMOTE_STANDARD_FMI1, sizeof standard);
    }
    char *argv[] = {r->host_path, r->binary_path, r->model_identifier, standard, NULL};
    char reason_of_start[512];
    if (child_process_start(argv, REMOTE_SOCKET_FD, &r->pid, &r->socket, reason_of_start,
                            sizeof reason_of_start) != 0) {
        r->pid = 0;
        r->socket = -1;
        snprintf(error, error_size, "the FMU host %s: %s", r->host_path, reason_of_start);
        return -1;
    }
    remote_reply hello;
    channel_receive_result got = channel_receive(r->socket, &hello, sizeof hello,
                                                 call_deadline(r), r->pid, NULL);
    if (got == CHANNEL_RECEIVED && hello.kind == REPLY_HELLO && hello.status == 0 && hello.payload == 0) {
        r->exported = hello.value;
        r->gone[0] = '\0';
        return 0;
    }
    char reason[1024] = "";
    if (got == CHANNEL_RECEIVED && hello.kind == REPLY_HELLO && hello.payload > 0 &&
        hello.payload < sizeof reason &&
        channel_receive(r->socket, reason, (size_t)hello.payload, CHANNEL_NO_DEADLINE, r->pid,
                        NULL) == CHANNEL_RECEIVED) {
        reason[hello.payload] = '\0';
    }
    if (got == CHANNEL_TIMED_OUT) {
        child_process_kill(r->pid);
    }
    char how[256];
    close_host(r, how, sizeof how);
    if (reason[0] != '\0') {
        snprintf(error, error_size, "%s", reason);
    } else {
        snprintf(error, error_size, "the FMU host %s %s before it loaded %s", r->host_path,
                 got == CHANNEL_TIMED_OUT ? "was killed: it hung" : how, r->binary_path);
    }
    return -1;
}

ssx_remote *ssx_remote_start(const char *host_path, const char *binary_path,
                             const char *model_identifier, int fmi1, double call_timeout,
                             char *error, size_t error_size)
{
    ssx_remote *r = calloc(1, sizeof *r);
    if (r == NULL) {
        snprintf(error, error_size, "out of memory starting the FMU host");
        return NULL;
    }
    r->socket = -1;
    r->call_timeout = call_timeout;
    r->fmi1 = fmi1;
    r->host_path = strdup(host_path);
    r->binary_path = strdup(binary_path);
    r->model_identifier = strdup(model_identifier);
    if (r->host_path == NULL || r->binary_path == NULL || r->model_identifier == NULL) {
        snprintf(error, error_size, "out of memory starting the FMU host");
        ssx_remote_stop(r);
        return NULL;
    }
    if (start_host(r, error, error_size) != 0) {
        ssx_remote_stop(r);
        return NULL;
    }
    return r;
}

void ssx_remote_stop(ssx_remote *r)
{
    if (r == NULL) {
        return;
    }
    char how[256];
    close_host(r, how, sizeof how); /* the host ends when its socket closes */
    free(r->host_path);
    free(r->binary_path);
    free(r->model_identifier);
    free(r->instance_name);
    free(r->buffer);
    free(r->read_after_step);
    free(r->read_values);
    free(r);
}

void ssx_remote_restart(ssx_remote *r)
{
    if (r->pid > 0) {
        child_process_kill(r->pid);
    }
    char how[256];
    close_host(r, how, sizeof how);
}

/* ------------------------------------------------------------------ one call */

/* What the host sent as the FMU's message, kept as its last message (the engine's logger would
 * read a '%' in it as a conversion). */
static void deliver(const ssx_remote *r, const char *text)
{
    if (r->fmi1) { /* FMI 1.0 hands the FMU no environment: the call in progress is this FMU's */
        ssx_fmu_environment *calling = ssx_fmu_environment_calling();
        if (calling != NULL && calling->remote == r) {
            ssx_fmu_environment_log(calling, text);
        }
    } else if (r->handed != NULL) {
        ssx_fmu_environment_log(ssx_fmu_environment_claimed(r->handed), text);
    }
}

/* The name of `call` in the binary's standard, for messages. */
static const char *call_name(const ssx_remote *r, remote_call call)
{
    return r->fmi1 && remote_fmi1_call_names[call] != NULL ? remote_fmi1_call_names[call]
                                                           : remote_call_names[call];
}

/* The host died, hung or broke the protocol during `call`: it is gone, and the call fails. */
static int lost(ssx_remote *r, remote_call call, channel_receive_result why)
{
    char how[256];
    if (why == CHANNEL_TIMED_OUT) {
        child_process_kill_group(r->pid);
        close_host(r, how, sizeof how);
        snprintf(r->gone, sizeof r->gone,
                 "%s did not return within the step timeout of %g s: the FMU process was "
                 "killed", call_name(r, call), r->call_timeout);
    } else if (why == CHANNEL_STOPPED) {
        child_process_kill_group(r->pid);
        close_host(r, how, sizeof how);
        snprintf(r->gone, sizeof r->gone,
                 "the run was stopped (an interrupt or its timeout) while %s was running: the "
                 "FMU process was killed", call_name(r, call));
    } else {
        close_host(r, how, sizeof how);
        snprintf(r->gone, sizeof r->gone, "the FMU process %s in %s", how,
                 call_name(r, call));
    }
    deliver(r, r->gone);
    return fmi2Fatal;
}

/* Sends the request (its payload staged in r->buffer) and waits for the result, handing the
 * FMU's messages to the logger meanwhile. The result's payload, which must be exactly
 * out_size bytes, goes to out. */
static int call(ssx_remote *r, remote_request *rq, void *out, size_t out_size, uint64_t *value)
{
    r->read_ready = 0;
    if (r->pid == 0) {
        deliver(r, r->gone);
        return fmi2Fatal;
    }
    double deadline = call_deadline(r);
    if (channel_send(r->socket, rq, sizeof *rq, r->buffer, (size_t)rq->payload) != 0) {
        return lost(r, rq->call, CHANNEL_PEER_GONE);
    }
    for (;;) {
        remote_reply reply;
        channel_receive_result got = channel_receive(r->socket, &reply, sizeof reply, deadline,
                                                     r->pid, &r->watch);
        /* a reply the host would never send (the FMU wrote to the socket itself) ends it */
        if (got == CHANNEL_RECEIVED && (reply.payload >= SIZE_MAX / 2 ||
                                reserve(r, (size_t)reply.payload + 1) != 0)) {
            got = CHANNEL_PEER_GONE;
        }
        if (got == CHANNEL_RECEIVED) {
            got = channel_receive(r->socket, r->buffer, (size_t)reply.payload, deadline, r->pid,
                                  &r->watch);
        }
        if (got != CHANNEL_RECEIVED) {
            return lost(r, rq->call, got);
        }
        if (reply.kind == REPLY_LOG) {
            r->buffer[reply.payload] = '\0';
            /* the category, then the text */
            size_t category_size = strnlen(r->buffer, (size_t)reply.payload) + 1;
            deliver(r, category_size < reply.payload ? r->buffer + category_size : "");
            continue;
        }
        if (reply.kind != REPLY_RESULT || reply.payload != out_size) {
            return lost(r, rq->call, CHANNEL_PEER_GONE);
        }
        if (out_size > 0) {
            memcpy(out, r->buffer, out_size);
        }
        if (value != NULL) {
            *value = reply.value;
        }
        return reply.status;
    }
}

/* Stages the payload parts of a request in r->buffer. */
static int stage(ssx_remote *r, remote_request *rq, const void *first, size_t first_size,
                 const void *second, size_t second_size, const void *third, size_t third_size)
{
    size_t size = first_size + second_size + third_size;
    if (reserve(r, size) != 0) {
        return -1;
    }
    if (first_size > 0) {
        memcpy(r->buffer, first, first_size);
    }
    if (second_size > 0) {
        memcpy(r->buffer + first_size, second, second_size);
    }
    if (third_size > 0) {
        memcpy(r->buffer + first_size + second_size, third, third_size);
    }
    rq->payload = size;
    return 0;
}

static int simple_call(fmi2Component c, remote_call which)
{
    remote_request rq = {.call = which};
    return call(c, &rq, NULL, 0, NULL);
}

/* ------------------------------------------------------------------ the fmi2 functions */

/* handed: what the FMU's callbacks name as their environment (FMI 2.0; NULL for FMI 1.0). */
static ssx_remote *instantiate_in_host(ssx_remote *r, const void *handed,
                                       const char *instance_name, int type, const char *guid,
                                       const char *resource_uri, int visible, int logging_on)
{
    instance_name = instance_name != NULL ? instance_name : "";
    guid = guid != NULL ? guid : "";
    resource_uri = resource_uri != NULL ? resource_uri : "";
    r->handed = handed;
    free(r->instance_name);
    r->instance_name = strdup(instance_name);
    if (r->pid == 0) { /* the last host died: this instance gets a new one */
        char error[1024];
        if (start_host(r, error, sizeof error) != 0) {
            deliver(r, error);
            return NULL;
        }
    }
    size_t sizes[3] = {strlen(instance_name) + 1, strlen(guid) + 1, strlen(resource_uri) + 1};
    remote_request rq = {.call = CALL_INSTANTIATE, .flag = (uint32_t)visible,
                         .flag2 = (uint32_t)logging_on, .n = (uint64_t)type};
    if (r->instance_name == NULL ||
        stage(r, &rq, instance_name, sizes[0], guid, sizes[1], resource_uri, sizes[2]) != 0) {
        deliver(r, "out of memory instantiating the isolated FMU");
        return NULL;
    }
    return call(r, &rq, NULL, 0, NULL) == fmi2OK ? r : NULL;
}

static fmi2Component remote_instantiate(fmi2String instance_name, fmi2Type type,
                                        fmi2String guid, fmi2String resource_uri,
                                        const fmi2CallbackFunctions *callbacks,
                                        fmi2Boolean visible, fmi2Boolean logging_on)
{
    const ssx_fmu_environment *environment = callbacks->componentEnvironment;
    return instantiate_in_host(environment->remote, environment, instance_name, (int)type, guid,
                               resource_uri, visible, logging_on);
}

static void remote_free_instance(fmi2Component c)
{
    ssx_remote *r = c;
    if (r->pid != 0) {
        (void)simple_call(r, CALL_FREE_INSTANCE);
    }
}

static fmi2Status remote_setup_experiment(fmi2Component c, fmi2Boolean tolerance_defined,
                                          fmi2Real tolerance, fmi2Real start_time,
                                          fmi2Boolean stop_time_defined, fmi2Real stop_time)
{
    remote_request rq = {.call = CALL_SETUP_EXPERIMENT, .flag = (uint32_t)tolerance_defined,
                         .flag2 = (uint32_t)stop_time_defined, .a = tolerance, .b = start_time,
                         .c = stop_time};
    return call(c, &rq, NULL, 0, NULL);
}

static fmi2Status remote_enter_initialization_mode(fmi2Component c)
{
    return simple_call(c, CALL_ENTER_INITIALIZATION_MODE);
}

static fmi2Status remote_exit_initialization_mode(fmi2Component c)
{
    return simple_call(c, CALL_EXIT_INITIALIZATION_MODE);
}

static fmi2Status remote_terminate(fmi2Component c)
{
    return simple_call(c, CALL_TERMINATE);
}

static fmi2Status remote_reset(fmi2Component c)
{
    return simple_call(c, CALL_RESET);
}

/* flag: noSetFMUStatePriorToCurrentPoint (FMI 2.0) or newStep (FMI 1.0) */
static int do_step(ssx_remote *r, double t, double h, uint32_t flag)
{
    size_t n = r->n_read_after_step;
    remote_request rq = {.call = CALL_DO_STEP, .flag = flag, .a = t, .b = h, .n = n};
    if (stage(r, &rq, r->read_after_step, n * sizeof *r->read_after_step, NULL, 0, NULL, 0) !=
        0) {
        return fmi2Error;
    }
    uint64_t read_status = REMOTE_NOT_READ;
    int status = call(r, &rq, r->read_values, n * sizeof *r->read_values, &read_status);
    if (status <= fmi2Warning && n > 0 && read_status != REMOTE_NOT_READ) {
        r->read_status = (int)read_status;
        r->read_ready = 1;
    }
    return status;
}

static fmi2Status remote_do_step(fmi2Component c, fmi2Real t, fmi2Real h,
                                 fmi2Boolean no_set_state_prior)
{
    return do_step(c, t, h, (uint32_t)no_set_state_prior);
}

/* Remembers which outputs to read after each step: the last list read with fmi2GetReal. */
static void read_after_steps(ssx_remote *r, const fmi2ValueReference *vr, size_t n)
{
    if (n == r->n_read_after_step &&
        (n == 0 || memcmp(vr, r->read_after_step, n * sizeof *vr) == 0)) {
        return;
    }
    fmi2ValueReference *list = realloc(r->read_after_step, n * sizeof *vr + 1);
    double *values = realloc(r->read_values, n * sizeof *values + 1);
    if (list != NULL) {
        r->read_after_step = list;
    }
    if (values != NULL) {
        r->read_values = values;
    }
    /* without room the steps read nothing ahead: slower, never wrong */
    r->n_read_after_step = list != NULL && values != NULL ? n : 0;
    if (n > 0 && r->n_read_after_step == n) {
        memcpy(r->read_after_step, vr, n * sizeof *vr);
    }
}

static int get_values(ssx_remote *r, remote_call which, const fmi2ValueReference *vr, size_t n,
                      void *values, size_t item)
{
    remote_request rq = {.call = which, .n = n};
    if (stage(r, &rq, vr, n * sizeof *vr, NULL, 0, NULL, 0) != 0) {
        return fmi2Error;
    }
    return call(r, &rq, values, n * item, NULL);
}

static int set_values(ssx_remote *r, remote_call which, const fmi2ValueReference *vr, size_t n,
                      const void *values, size_t item)
{
    remote_request rq = {.call = which, .n = n};
    if (stage(r, &rq, values, n * item, vr, n * sizeof *vr, NULL, 0) != 0) {
        return fmi2Error;
    }
    return call(r, &rq, NULL, 0, NULL);
}

static int get_reals(ssx_remote *r, const fmi2ValueReference vr[], size_t n, double values[])
{
    if (r->read_ready && n == r->n_read_after_step &&
        memcmp(vr, r->read_after_step, n * sizeof *vr) == 0) {
        r->read_ready = 0;
        memcpy(values, r->read_values, n * sizeof *values);
        return r->read_status;
    }
    int status = get_values(r, CALL_GET_REAL, vr, n, values, sizeof *values);
    read_after_steps(r, vr, n);
    return status;
}

static fmi2Status remote_get_real(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                  fmi2Real values[])
{
    return get_reals(c, vr, n, values);
}

static fmi2Status remote_get_integer(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                     fmi2Integer values[])
{
    return get_values(c, CALL_GET_INTEGER, vr, n, values, sizeof *values);
}

static fmi2Status remote_get_boolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                     fmi2Boolean values[])
{
    return get_values(c, CALL_GET_BOOLEAN, vr, n, values, sizeof *values);
}

static fmi2Status remote_set_real(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                  const fmi2Real values[])
{
    return set_values(c, CALL_SET_REAL, vr, n, values, sizeof *values);
}

static fmi2Status remote_set_integer(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                     const fmi2Integer values[])
{
    return set_values(c, CALL_SET_INTEGER, vr, n, values, sizeof *values);
}

static fmi2Status remote_set_boolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                     const fmi2Boolean values[])
{
    return set_values(c, CALL_SET_BOOLEAN, vr, n, values, sizeof *values);
}

static fmi2Status remote_get_state(fmi2Component c, fmi2FMUstate *state)
{
    remote_request rq = {.call = CALL_GET_FMU_STATE, .state = state_number(*state)};
    uint64_t value = 0;
    int status = call(c, &rq, NULL, 0, &value);
    if (status <= fmi2Warning) {
        *state = state_pointer(value);
    }
    return status;
}

static fmi2Status remote_set_state(fmi2Component c, fmi2FMUstate state)
{
    remote_request rq = {.call = CALL_SET_FMU_STATE, .state = state_number(state)};
    return call(c, &rq, NULL, 0, NULL);
}

static fmi2Status remote_free_state(fmi2Component c, fmi2FMUstate *state)
{
    ssx_remote *r = c;
    remote_request rq = {.call = CALL_FREE_FMU_STATE, .state = state_number(*state)};
    /* a dead host took its states with it */
    int status = r->pid != 0 ? call(r, &rq, NULL, 0, NULL) : fmi2OK;
    *state = NULL;
    return status;
}

static fmi2Status remote_serialized_state_size(fmi2Component c, fmi2FMUstate state,
                                               size_t *size)
{
    remote_request rq = {.call = CALL_SERIALIZED_FMU_STATE_SIZE, .state = state_number(state)};
    uint64_t value = 0;
    int status = call(c, &rq, NULL, 0, &value);
    *size = (size_t)value;
    return status;
}

static fmi2Status remote_serialize_state(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[],
                                         size_t size)
{
    remote_request rq = {.call = CALL_SERIALIZE_FMU_STATE, .state = state_number(state),
                         .n = size};
    return call(c, &rq, bytes, size, NULL);
}

static fmi2Status remote_deserialize_state(fmi2Component c, const fmi2Byte bytes[], size_t size,
                                           fmi2FMUstate *state)
{
    ssx_remote *r = c;
    remote_request rq = {.call = CALL_DESERIALIZE_FMU_STATE, .state = state_number(*state),
                         .n = size};
    if (stage(r, &rq, bytes, size, NULL, 0, NULL, 0) != 0) {
        return fmi2Error;
    }
    uint64_t value = 0;
    int status = call(r, &rq, NULL, 0, &value);
    if (status <= fmi2Warning) {
        *state = state_pointer(value);
    }
    return status;
}

static fmi2Status remote_get_directional_derivative(fmi2Component c,
                                                    const fmi2ValueReference unknowns[],
                                                    size_t n_unknowns,
                                                    const fmi2ValueReference knowns[],
                                                    size_t n_knowns, const fmi2Real seeds[],
                                                    fmi2Real derivatives[])
{
    ssx_remote *r = c;
    remote_request rq = {.call = CALL_GET_DIRECTIONAL_DERIVATIVE, .n = n_unknowns,
                         .n2 = n_knowns};
    if (stage(r, &rq, seeds, n_knowns * sizeof *seeds, unknowns,
              n_unknowns * sizeof *unknowns, knowns, n_knowns * sizeof *knowns) != 0) {
        return fmi2Error;
    }
    return call(r, &rq, derivatives, n_unknowns * sizeof *derivatives, NULL);
}

/* ------------------------------------------------------------------ the FMI 1.0 functions */

/* FMI 1.0 hands the FMU no environment: the remote is that of the FMU the binding is calling
 * on this thread (it marks instantiation too), and messages go to that FMU (deliver). */
static fmi1Component remote1_instantiate_slave(fmi1String instance_name, fmi1String guid,
                                               fmi1String fmu_location, fmi1String mime_type,
                                               fmi1Real timeout, fmi1Boolean visible,
                                               fmi1Boolean interactive,
                                               fmi1CallbackFunctions callbacks,
                                               fmi1Boolean logging_on)
{
    (void)mime_type;
    (void)timeout;
    (void)interactive;
    (void)callbacks; /* the host hands the FMU its own */
    ssx_fmu_environment *environment = ssx_fmu_environment_calling();
    if (environment == NULL || environment->remote == NULL) {
        return NULL;
    }
    return instantiate_in_host(environment->remote, NULL, instance_name, 0, guid, fmu_location,
                               visible != fmi1False, logging_on != fmi1False);
}

static void remote1_free_slave_instance(fmi1Component c)
{
    remote_free_instance(c);
}

static fmi1Status remote1_initialize_slave(fmi1Component c, fmi1Real start_time,
                                           fmi1Boolean stop_time_defined, fmi1Real stop_time)
{
    remote_request rq = {.call = CALL_EXIT_INITIALIZATION_MODE,
                         .flag2 = stop_time_defined != fmi1False, .b = start_time,
                         .c = stop_time};
    return (fmi1Status)call(c, &rq, NULL, 0, NULL);
}

static fmi1Status remote1_terminate_slave(fmi1Component c)
{
    return (fmi1Status)simple_call(c, CALL_TERMINATE);
}

static fmi1Status remote1_reset_slave(fmi1Component c)
{
    return (fmi1Status)simple_call(c, CALL_RESET);
}

static fmi1Status remote1_do_step(fmi1Component c, fmi1Real t, fmi1Real h, fmi1Boolean new_step)
{
    return (fmi1Status)do_step(c, t, h, new_step != fmi1False);
}

static fmi1Status remote1_get_real(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                   fmi1Real values[])
{
    return (fmi1Status)get_reals(c, vr, n, values);
}

static fmi1Status remote1_get_integer(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                      fmi1Integer values[])
{
    return (fmi1Status)get_values(c, CALL_GET_INTEGER, vr, n, values, sizeof *values);
}

static fmi1Status remote1_set_real(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                   const fmi1Real values[])
{
    return (fmi1Status)set_values(c, CALL_SET_REAL, vr, n, values, sizeof *values);
}

static fmi1Status remote1_set_integer(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                      const fmi1Integer values[])
{
    return (fmi1Status)set_values(c, CALL_SET_INTEGER, vr, n, values, sizeof *values);
}

/* Booleans cross as ints (the host narrows them to fmiBoolean): in chunks on the stack. */
enum { BOOLEAN_CHUNK = 64 };

static fmi1Status remote1_get_boolean(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                      fmi1Boolean values[])
{
    int worst = fmi2OK;
    for (size_t first = 0; first < n && worst <= fmi2Warning; first += BOOLEAN_CHUNK) {
        fmi2Boolean chunk[BOOLEAN_CHUNK];
        size_t count = n - first < BOOLEAN_CHUNK ? n - first : BOOLEAN_CHUNK;
        int status = get_values(c, CALL_GET_BOOLEAN, vr + first, count, chunk, sizeof *chunk);
        for (size_t i = 0; i < count; ++i) {
            values[first + i] = chunk[i] ? fmi1True : fmi1False;
        }
        worst = status > worst ? status : worst;
    }
    return (fmi1Status)worst;
}

static fmi1Status remote1_set_boolean(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                      const fmi1Boolean values[])
{
    int worst = fmi2OK;
    for (size_t first = 0; first < n && worst <= fmi2Warning; first += BOOLEAN_CHUNK) {
        fmi2Boolean chunk[BOOLEAN_CHUNK];
        size_t count = n - first < BOOLEAN_CHUNK ? n - first : BOOLEAN_CHUNK;
        for (size_t i = 0; i < count; ++i) {
            chunk[i] = values[first + i] != fmi1False;
        }
        int status = set_values(c, CALL_SET_BOOLEAN, vr + first, count, chunk, sizeof *chunk);
        worst = status > worst ? status : worst;
    }
    return (fmi1Status)worst;
}

void *ssx_remote_function(const ssx_remote *r, const char *name)
{
    void (*const fmi1_forwarders[CALL_COUNT])(void) = {
        [CALL_INSTANTIATE] = (void (*)(void))remote1_instantiate_slave,
        [CALL_FREE_INSTANCE] = (void (*)(void))remote1_free_slave_instance,
        [CALL_EXIT_INITIALIZATION_MODE] = (void (*)(void))remote1_initialize_slave,
        [CALL_TERMINATE] = (void (*)(void))remote1_terminate_slave,
        [CALL_RESET] = (void (*)(void))remote1_reset_slave,
        [CALL_GET_REAL] = (void (*)(void))remote1_get_real,
        [CALL_GET_INTEGER] = (void (*)(void))remote1_get_integer,
        [CALL_GET_BOOLEAN] = (void (*)(void))remote1_get_boolean,
        [CALL_SET_REAL] = (void (*)(void))remote1_set_real,
        [CALL_SET_INTEGER] = (void (*)(void))remote1_set_integer,
        [CALL_SET_BOOLEAN] = (void (*)(void))remote1_set_boolean,
        [CALL_DO_STEP] = (void (*)(void))remote1_do_step,
    };
    void (*const forwarders[CALL_COUNT])(void) = {
        [CALL_INSTANTIATE] = (void (*)(void))remote_instantiate,
        [CALL_FREE_INSTANCE] = (void (*)(void))remote_free_instance,
        [CALL_SETUP_EXPERIMENT] = (void (*)(void))remote_setup_experiment,
        [CALL_ENTER_INITIALIZATION_MODE] = (void (*)(void))remote_enter_initialization_mode,
        [CALL_EXIT_INITIALIZATION_MODE] = (void (*)(void))remote_exit_initialization_mode,
        [CALL_TERMINATE] = (void (*)(void))remote_terminate,
        [CALL_RESET] = (void (*)(void))remote_reset,
        [CALL_GET_REAL] = (void (*)(void))remote_get_real,
        [CALL_GET_INTEGER] = (void (*)(void))remote_get_integer,
        [CALL_GET_BOOLEAN] = (void (*)(void))remote_get_boolean,
        [CALL_SET_REAL] = (void (*)(void))remote_set_real,
        [CALL_SET_INTEGER] = (void (*)(void))remote_set_integer,
        [CALL_SET_BOOLEAN] = (void (*)(void))remote_set_boolean,
        [CALL_DO_STEP] = (void (*)(void))remote_do_step,
        [CALL_GET_FMU_STATE] = (void (*)(void))remote_get_state,
        [CALL_SET_FMU_STATE] = (void (*)(void))remote_set_state,
        [CALL_FREE_FMU_STATE] = (void (*)(void))remote_free_state,
        [CALL_SERIALIZED_FMU_STATE_SIZE] = (void (*)(void))remote_serialized_state_size,
        [CALL_SERIALIZE_FMU_STATE] = (void (*)(void))remote_serialize_state,
        [CALL_DESERIALIZE_FMU_STATE] = (void (*)(void))remote_deserialize_state,
        [CALL_GET_DIRECTIONAL_DERIVATIVE] = (void (*)(void))remote_get_directional_derivative,
    };
    const char *const *names = r->fmi1 ? remote_fmi1_call_names : remote_call_names;
    for (int i = 0; i < CALL_COUNT; ++i) {
        if (names[i] != NULL && strcmp(name, names[i]) == 0 && (r->exported >> i) & 1u) {
            void *symbol;
            /* the dlsym convention: a function travels as void * */
            memcpy(&symbol, r->fmi1 ? &fmi1_forwarders[i] : &forwarders[i], sizeof symbol);
            return symbol;
        }
    }
    return NULL;
}

void ssx_remote_set_watch(ssx_remote *r, int (*stop)(void *user), void *user)
{
    if (r != NULL) {
        r->watch = (channel_watch){stop, user};
    }
}
