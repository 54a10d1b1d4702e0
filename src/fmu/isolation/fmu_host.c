/* The FMU host: runs one FMU binary in a process of its own for an isolated FMUComponent, so
 * that a crash, an abort or an endless loop in the FMU ends this process, not the user's.
 *
 *     syssimx-fmu-host <binary> <model identifier> fmi2|fmi1
 *
 * The engine starts it with the socket on descriptor REMOTE_SOCKET_FD (fmu_remote_protocol.h)
 * and forwards every fmi2 call (for an FMI 1.0 Co-Simulation binary, the fmi2 call that stands
 * for each FMI 1.0 function: remote_fmi1_call_names); the host makes the call and answers with
 * what the FMU logged and the call's result. It ends when the engine closes the socket, even while the FMU is
 * still inside a call (the engine's process died). */
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "channel.h"
#include "fmi1Functions.h"
#include "fmi2Functions.h"
#include "fmu_message.h"
#include "fmu_remote_protocol.h"
#include "shared_library.h"

typedef void (*any_function)(void);

typedef struct {
    int socket;
    int fmi1; /* the binary is FMI 1.0 Co-Simulation: fn holds remote_fmi1_call_names */
    any_function fn[CALL_COUNT];
    fmi2Component instance;
    fmi2CallbackFunctions callbacks; /* the FMU keeps the pointer: lives as long as the host */
    fmi1CallbackFunctions callbacks1;
    char *request;                   /* the request's payload */
    size_t request_capacity;
    char *reply;                     /* the result's payload */
    size_t reply_capacity;
} host;

static void *grown(char **buffer, size_t *capacity, size_t size)
{
    if (size > *capacity) {
        char *bigger = realloc(*buffer, size);
        if (bigger == NULL) {
            return NULL;
        }
        *buffer = bigger;
        *capacity = size;
    }
    return *buffer;
}

static int send_reply(const host *h, remote_reply_kind kind, int status, uint64_t value,
                      const void *payload, size_t size)
{
    remote_reply reply = {.kind = kind, .status = status, .value = value, .payload = size};
    return channel_send(h->socket, &reply, sizeof reply, payload, size);
}

/* What the host hands the FMU as its callbacks' environment: a mark to compare, never read,
 * for some FMUs hand back something else (1, 2, NULL). The logger needs no state of the host:
 * the engine's end of the socket is always on REMOTE_SOCKET_FD. */
static const char handed_environment;

/* Sent while the call runs: the engine keeps it as the FMU's last message. */
static void send_log(int status, const char *category, const char *attribution,
                     const char *message, va_list args)
{
    char text[2048];
    size_t category_size = strlen(category != NULL ? category : "") + 1;
    if (category_size > 256) {
        category_size = 256;
    }
    memcpy(text, category != NULL ? category : "", category_size - 1);
    text[category_size - 1] = '\0';
    size_t attribution_size = strlen(attribution);
    memcpy(text + category_size, attribution, attribution_size + 1);
    ssx_format_fmu_message(text + category_size + attribution_size,
                           sizeof text - category_size - attribution_size, message, args);
    size_t size = category_size + strlen(text + category_size) + 1;
    remote_reply reply = {.kind = REPLY_LOG, .status = status, .payload = size};
    (void)channel_send(REMOTE_SOCKET_FD, &reply, sizeof reply, text, size);
}

/* A message naming another environment is still the FMU's (the host runs no other),
 * attributed to "an FMU". */
static void logger(fmi2ComponentEnvironment environment, fmi2String instance_name,
                   fmi2Status status, fmi2String category, fmi2String message, ...)
{
    (void)instance_name;
    if (message == NULL) {
        return;
    }
    va_list args;
    va_start(args, message);
    send_log((int)status, category, environment == &handed_environment ? "" : "an FMU: ",
             message, args);
    va_end(args);
}

/* FMI 1.0 names the FMU's component, not an environment: every message is the FMU's. */
static void logger1(fmi1Component component, fmi1String instance_name, fmi1Status status,
                    fmi1String category, fmi1String message, ...)
{
    (void)component;
    (void)instance_name;
    if (message == NULL) {
        return;
    }
    va_list args;
    va_start(args, message);
    send_log((int)status, category, "", message, args);
    va_end(args);
}

/* The fmi2 function of a call, as its own type. */
#define FN(type, call) ((type *)h->fn[call])

/* After a doStep that returned `status`: the n outputs the request names, read in the same
 * round trip when the step succeeded (their getReal status in *value), zeros otherwise.
 * FMI 1.0 and 2.0 share the statuses, value references and reals this needs. */
static int step_reply(host *h, int status, size_t n, uint64_t *value, size_t *reply_size)
{
    double *out = grown(&h->reply, &h->reply_capacity, n * sizeof(double));
    if (out == NULL && n > 0) {
        return fmi2Fatal;
    }
    *reply_size = n * sizeof(double);
    *value = REMOTE_NOT_READ;
    if (n == 0) {
        return status;
    }
    if (status > fmi2Warning) {
        memset(out, 0, n * sizeof(double));
        return status;
    }
    const unsigned int *vr = (const unsigned int *)h->request;
    *value = h->fmi1 ? (uint64_t)FN(fmi1GetRealTYPE, CALL_GET_REAL)(h->instance, vr, n, out)
                     : (uint64_t)FN(fmi2GetRealTYPE, CALL_GET_REAL)(h->instance, vr, n, out);
    return status;
}

/* Makes the call. Returns its fmi2Status; *value and *reply_size describe the result. */
static int serve(host *h, const remote_request *rq, uint64_t *value, size_t *reply_size)
{
    const char *in = h->request;
    size_t n = (size_t)rq->n;
    switch ((remote_call)rq->call) {
    case CALL_INSTANTIATE: {
        const char *name = in;
        const char *guid = name + strlen(name) + 1;
        const char *resources = guid + strlen(guid) + 1;
        h->instance = FN(fmi2InstantiateTYPE, CALL_INSTANTIATE)(
            name, (fmi2Type)rq->n, guid, resources, &h->callbacks, (fmi2Boolean)rq->flag,
            (fmi2Boolean)rq->flag2);
        return h->instance != NULL ? fmi2OK : -1;
    }
    case CALL_FREE_INSTANCE:
        FN(fmi2FreeInstanceTYPE, CALL_FREE_INSTANCE)(h->instance);
        h->instance = NULL;
        return fmi2OK;
    case CALL_SETUP_EXPERIMENT:
        return FN(fmi2SetupExperimentTYPE, CALL_SETUP_EXPERIMENT)(
            h->instance, (fmi2Boolean)rq->flag, rq->a, rq->b, (fmi2Boolean)rq->flag2, rq->c);
    case CALL_ENTER_INITIALIZATION_MODE:
        return FN(fmi2EnterInitializationModeTYPE, rq->call)(h->instance);
    case CALL_EXIT_INITIALIZATION_MODE:
        return FN(fmi2ExitInitializationModeTYPE, rq->call)(h->instance);
    case CALL_TERMINATE:
        return FN(fmi2TerminateTYPE, rq->call)(h->instance);
    case CALL_RESET:
        return FN(fmi2ResetTYPE, rq->call)(h->instance);
    case CALL_DO_STEP:
        return step_reply(h, FN(fmi2DoStepTYPE, rq->call)(h->instance, rq->a, rq->b,
                                                          (fmi2Boolean)rq->flag),
                          n, value, reply_size);
    case CALL_GET_REAL:
    case CALL_GET_INTEGER:
    case CALL_GET_BOOLEAN: {
        size_t item = rq->call == CALL_GET_REAL ? sizeof(fmi2Real) : sizeof(fmi2Integer);
        void *out = grown(&h->reply, &h->reply_capacity, n * item);
        if (out == NULL && n > 0) {
            return fmi2Fatal;
        }
        *reply_size = n * item;
        const fmi2ValueReference *vr = (const fmi2ValueReference *)in;
        if (rq->call == CALL_GET_REAL) {
            return FN(fmi2GetRealTYPE, rq->call)(h->instance, vr, n, out);
        }
        if (rq->call == CALL_GET_INTEGER) {
            return FN(fmi2GetIntegerTYPE, rq->call)(h->instance, vr, n, out);
        }
        return FN(fmi2GetBooleanTYPE, rq->call)(h->instance, vr, n, out);
    }
    case CALL_SET_REAL:
        return FN(fmi2SetRealTYPE, rq->call)(
            h->instance, (const fmi2ValueReference *)(in + n * sizeof(fmi2Real)), n,
            (const fmi2Real *)in);
    case CALL_SET_INTEGER:
        return FN(fmi2SetIntegerTYPE, rq->call)(
            h->instance, (const fmi2ValueReference *)(in + n * sizeof(fmi2Integer)), n,
            (const fmi2Integer *)in);
    case CALL_SET_BOOLEAN:
        return FN(fmi2SetBooleanTYPE, rq->call)(
            h->instance, (const fmi2ValueReference *)(in + n * sizeof(fmi2Boolean)), n,
            (const fmi2Boolean *)in);
    case CALL_GET_FMU_STATE: {
        fmi2FMUstate state = state_pointer(rq->state);
        int status = FN(fmi2GetFMUstateTYPE, rq->call)(h->instance, &state);
        *value = state_number(state);
        return status;
    }
    case CALL_SET_FMU_STATE:
        return FN(fmi2SetFMUstateTYPE, rq->call)(h->instance, state_pointer(rq->state));
    case CALL_FREE_FMU_STATE: {
        fmi2FMUstate state = state_pointer(rq->state);
        return FN(fmi2FreeFMUstateTYPE, rq->call)(h->instance, &state);
    }
    case CALL_SERIALIZED_FMU_STATE_SIZE: {
        size_t size = 0;
        int status = FN(fmi2SerializedFMUstateSizeTYPE, rq->call)(
            h->instance, state_pointer(rq->state), &size);
        *value = size;
        return status;
    }
    case CALL_SERIALIZE_FMU_STATE: {
        char *out = grown(&h->reply, &h->reply_capacity, n);
        if (out == NULL && n > 0) {
            return fmi2Fatal;
        }
        *reply_size = n;
        return FN(fmi2SerializeFMUstateTYPE, rq->call)(h->instance, state_pointer(rq->state),
                                                       out, n);
    }
    case CALL_DESERIALIZE_FMU_STATE: {
        fmi2FMUstate state = state_pointer(rq->state);
        int status = FN(fmi2DeSerializeFMUstateTYPE, rq->call)(h->instance, in, n, &state);
        *value = state_number(state);
        return status;
    }
    case CALL_GET_DIRECTIONAL_DERIVATIVE: {
        size_t n_knowns = (size_t)rq->n2;
        const fmi2Real *seeds = (const fmi2Real *)in;
        const fmi2ValueReference *unknowns = (const fmi2ValueReference *)(seeds + n_knowns);
        fmi2Real *out = grown(&h->reply, &h->reply_capacity, n * sizeof(fmi2Real));
        if (out == NULL && n > 0) {
            return fmi2Fatal;
        }
        *reply_size = n * sizeof(fmi2Real);
        return FN(fmi2GetDirectionalDerivativeTYPE, rq->call)(
            h->instance, unknowns, n, unknowns + n, n_knowns, seeds, out);
    }
    case CALL_COUNT:
        break;
    }
    return fmi2Fatal;
}

/* fmiBoolean is a char: the engine's ints are narrowed and widened through a buffer. */
static int serve_fmi1_booleans(host *h, const remote_request *rq, size_t *reply_size)
{
    size_t n = (size_t)rq->n;
    const char *in = h->request;
    fmi1Boolean *chunk = malloc(n + 1);
    fmi2Boolean *out = grown(&h->reply, &h->reply_capacity, n * sizeof(fmi2Boolean));
    if (chunk == NULL || (out == NULL && n > 0)) {
        free(chunk);
        return fmi2Fatal;
    }
    int status;
    if (rq->call == CALL_GET_BOOLEAN) {
        *reply_size = n * sizeof(fmi2Boolean);
        status = FN(fmi1GetBooleanTYPE, rq->call)(h->instance, (const fmi1ValueReference *)in, n,
                                                  chunk);
        for (size_t i = 0; i < n; ++i) {
            out[i] = chunk[i] != fmi1False;
        }
    } else {
        const fmi2Boolean *values = (const fmi2Boolean *)in;
        for (size_t i = 0; i < n; ++i) {
            chunk[i] = values[i] ? fmi1True : fmi1False;
        }
        status = FN(fmi1SetBooleanTYPE, rq->call)(
            h->instance, (const fmi1ValueReference *)(in + n * sizeof(fmi2Boolean)), n, chunk);
    }
    free(chunk);
    return status;
}

/* The calls of an FMI 1.0 Co-Simulation binary (remote_fmi1_call_names); reals and integers
 * have the same types in both standards, so those calls are serve's. */
static int serve_fmi1(host *h, const remote_request *rq, uint64_t *value, size_t *reply_size)
{
    const char *in = h->request;
    size_t n = (size_t)rq->n;
    switch ((remote_call)rq->call) {
    case CALL_INSTANTIATE: {
        const char *name = in;
        const char *guid = name + strlen(name) + 1;
        const char *location = guid + strlen(guid) + 1;
        h->instance = FN(fmi1InstantiateSlaveTYPE, CALL_INSTANTIATE)(
            name, guid, location, "application/x-fmu-sharedlibrary", 0.0,
            rq->flag ? fmi1True : fmi1False, fmi1False, h->callbacks1,
            rq->flag2 ? fmi1True : fmi1False);
        return h->instance != NULL ? fmi2OK : -1;
    }
    case CALL_FREE_INSTANCE:
        FN(fmi1FreeSlaveInstanceTYPE, rq->call)(h->instance);
        h->instance = NULL;
        return fmi2OK;
    case CALL_EXIT_INITIALIZATION_MODE:
        return FN(fmi1InitializeSlaveTYPE, rq->call)(
            h->instance, rq->b, rq->flag2 ? fmi1True : fmi1False, rq->c);
    case CALL_TERMINATE:
        return FN(fmi1TerminateSlaveTYPE, rq->call)(h->instance);
    case CALL_RESET:
        return FN(fmi1ResetSlaveTYPE, rq->call)(h->instance);
    case CALL_DO_STEP:
        return step_reply(h, FN(fmi1DoStepTYPE, rq->call)(h->instance, rq->a, rq->b,
                                                          rq->flag ? fmi1True : fmi1False),
                          n, value, reply_size);
    case CALL_GET_REAL:
    case CALL_GET_INTEGER:
    case CALL_SET_REAL:
    case CALL_SET_INTEGER: {
        size_t item = rq->call == CALL_GET_REAL || rq->call == CALL_SET_REAL ? sizeof(fmi1Real)
                                                                            : sizeof(fmi1Integer);
        const fmi1ValueReference *vr = (const fmi1ValueReference *)in;
        if (rq->call == CALL_SET_REAL) {
            return FN(fmi1SetRealTYPE, rq->call)(
                h->instance, (const fmi1ValueReference *)(in + n * item), n,
                (const fmi1Real *)in);
        }
        if (rq->call == CALL_SET_INTEGER) {
            return FN(fmi1SetIntegerTYPE, rq->call)(
                h->instance, (const fmi1ValueReference *)(in + n * item), n,
                (const fmi1Integer *)in);
        }
        void *out = grown(&h->reply, &h->reply_capacity, n * item);
        if (out == NULL && n > 0) {
            return fmi2Fatal;
        }
        *reply_size = n * item;
        if (rq->call == CALL_GET_REAL) {
            return FN(fmi1GetRealTYPE, rq->call)(h->instance, vr, n, out);
        }
        return FN(fmi1GetIntegerTYPE, rq->call)(h->instance, vr, n, out);
    }
    case CALL_GET_BOOLEAN:
    case CALL_SET_BOOLEAN:
        return serve_fmi1_booleans(h, rq, reply_size);
    default:
        break;
    }
    return fmi2Fatal;
}

/* Unprefixed names first; FMUs compiled with FMI2_FUNCTION_PREFIX export <id>_fmi2Name, FMI 1.0
 * binaries always <id>_fmiName. */
static uint64_t resolve(host *h, void *library, const char *model_identifier)
{
    const char *const *names = h->fmi1 ? remote_fmi1_call_names : remote_call_names;
    uint64_t exported = 0;
    for (int call = 0; call < CALL_COUNT; ++call) {
        if (names[call] == NULL) {
            h->fn[call] = NULL;
            continue;
        }
        void *symbol = shared_library_symbol(library, names[call]);
        if (symbol == NULL && model_identifier[0] != '\0') {
            char prefixed[256];
            snprintf(prefixed, sizeof prefixed, "%s_%s", model_identifier, names[call]);
            symbol = shared_library_symbol(library, prefixed);
        }
        /* a symbol is a void *; C11 has no direct cast to a function pointer. */
        memcpy(&h->fn[call], &symbol, sizeof symbol);
        if (symbol != NULL) {
            exported |= UINT64_C(1) << call;
        }
    }
    return exported;
}

/* Reads requests and answers them until the engine closes the socket. */
static int serve_requests(host *h)
{
    for (;;) {
        remote_request rq;
        if (channel_receive(h->socket, &rq, sizeof rq, CHANNEL_NO_DEADLINE, 0, NULL) !=
            CHANNEL_RECEIVED) {
            return 0;
        }
        if (grown(&h->request, &h->request_capacity, (size_t)rq.payload) == NULL &&
            rq.payload > 0) {
            return 1;
        }
        if (channel_receive(h->socket, h->request, (size_t)rq.payload, CHANNEL_NO_DEADLINE, 0,
                            NULL) != CHANNEL_RECEIVED) {
            return 0;
        }
        /* A call the binary does not export never arrives: the engine knows the exports. */
        if (rq.call >= CALL_COUNT || h->fn[rq.call] == NULL) {
            return 1;
        }
        uint64_t value = 0;
        size_t reply_size = 0;
        int status = h->fmi1 ? serve_fmi1(h, &rq, &value, &reply_size)
                             : serve(h, &rq, &value, &reply_size);
        if (send_reply(h, REPLY_RESULT, status, value, h->reply, reply_size) != 0) {
            return 0;
        }
    }
}

/* Once the engine closed its end of the socket: the host ends, and what the FMU forked with
 * it (the host leads their process group; an engine that was killed cannot end them). */
static _Noreturn void end_with_forked_processes(void)
{
    kill(0, SIGKILL); /* the group, the host included */
    _Exit(0);
}

/* Ends the host when the engine's end of the socket closes. The main thread cannot notice
 * while the FMU runs away inside a call, and PR_SET_PDEATHSIG would fire when the engine's
 * thread that started the host ends, not its process. */
static void *watch_engine(void *socket)
{
    channel_wait_for_hangup(*(const int *)socket);
    end_with_forked_processes();
}

int main(int argc, char **argv)
{
    if (argc != 4 || (strcmp(argv[3], REMOTE_STANDARD_FMI2) != 0 &&
                      strcmp(argv[3], REMOTE_STANDARD_FMI1) != 0)) {
        fprintf(stderr, "usage: %s <FMU binary> <model identifier> %s|%s (started by "
                "syssimx)\n", argv[0], REMOTE_STANDARD_FMI2, REMOTE_STANDARD_FMI1);
        return 2;
    }
    host h = {.socket = REMOTE_SOCKET_FD, .fmi1 = strcmp(argv[3], REMOTE_STANDARD_FMI1) == 0};
    pthread_t watchdog;
    if (pthread_create(&watchdog, NULL, watch_engine, &h.socket) != 0) {
        fprintf(stderr, "%s: cannot start the watchdog thread\n", argv[0]);
        return 1;
    }
    h.callbacks.logger = logger;
    h.callbacks.allocateMemory = calloc;
    h.callbacks.freeMemory = free;
    h.callbacks.componentEnvironment = (fmi2ComponentEnvironment)&handed_environment;
    h.callbacks1 = (fmi1CallbackFunctions){logger1, calloc, free, NULL};
    const char *reason = NULL;
    void *library = shared_library_open(argv[1], &reason);
    if (library == NULL) {
        char text[1024];
        snprintf(text, sizeof text, "cannot load the FMU binary %s: %s", argv[1], reason);
        (void)send_reply(&h, REPLY_HELLO, -1, 0, text, strlen(text) + 1);
        return 1;
    }
    int failed = send_reply(&h, REPLY_HELLO, 0, resolve(&h, library, argv[2]), NULL, 0) != 0 ||
                 serve_requests(&h) != 0;
    if (!failed) { /* the engine closed the socket, maybe before the watchdog saw it */
        end_with_forked_processes();
    }
    free(h.request);
    free(h.reply);
    shared_library_close(library);
    return failed;
}
