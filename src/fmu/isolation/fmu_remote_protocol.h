/* The wire protocol between the engine (fmu_remote.c) and the FMU host process (fmu_host.c).
 *
 * One stream socket. The host starts by sending a HELLO reply: status 0 and the set of
 * functions the binary exports in `value` (bit i for remote_call i), or status -1 and the
 * reason as text. Then, for every request the engine sends, the host answers with any number
 * of LOG replies (what the FMU logged during the call) followed by one RESULT reply. Both ends
 * run on the same machine, so numbers travel in native byte order and doubles bit for bit. */
#ifndef SSX_FMU_REMOTE_PROTOCOL_H
#define SSX_FMU_REMOTE_PROTOCOL_H

#include <stddef.h>
#include <stdint.h>

/* The fmi2 calls the engine makes; their order indexes remote_call_names. */
typedef enum {
    CALL_INSTANTIATE,
    CALL_FREE_INSTANCE,
    CALL_SETUP_EXPERIMENT,
    CALL_ENTER_INITIALIZATION_MODE,
    CALL_EXIT_INITIALIZATION_MODE,
    CALL_TERMINATE,
    CALL_RESET,
    CALL_GET_REAL,
    CALL_GET_INTEGER,
    CALL_GET_BOOLEAN,
    CALL_SET_REAL,
    CALL_SET_INTEGER,
    CALL_SET_BOOLEAN,
    CALL_DO_STEP,
    CALL_GET_FMU_STATE,
    CALL_SET_FMU_STATE,
    CALL_FREE_FMU_STATE,
    CALL_SERIALIZED_FMU_STATE_SIZE,
    CALL_SERIALIZE_FMU_STATE,
    CALL_DESERIALIZE_FMU_STATE,
    CALL_GET_DIRECTIONAL_DERIVATIVE,
    CALL_COUNT
} remote_call;

static const char *const remote_call_names[CALL_COUNT] = {
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2DoStep",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
};

/* An FMI 1.0 Co-Simulation binary is served through the same calls: the host resolves the
 * function of this table in place of each fmi2 one (NULL: FMI 1.0 has none). Values cross as
 * for FMI 2.0 (a boolean as an int); ExitInitializationMode is fmiInitializeSlave, with the
 * start time in b, stopTimeDefined in flag2 and the stop time in c, as SetupExperiment sends
 * them; Instantiate's resource URI is the fmuLocation; DoStep's flag is newStep. */
static const char *const remote_fmi1_call_names[CALL_COUNT] = {
    [CALL_INSTANTIATE] = "fmiInstantiateSlave",
    [CALL_FREE_INSTANCE] = "fmiFreeSlaveInstance",
    [CALL_EXIT_INITIALIZATION_MODE] = "fmiInitializeSlave",
    [CALL_TERMINATE] = "fmiTerminateSlave",
    [CALL_RESET] = "fmiResetSlave",
    [CALL_GET_REAL] = "fmiGetReal",
    [CALL_GET_INTEGER] = "fmiGetInteger",
    [CALL_GET_BOOLEAN] = "fmiGetBoolean",
    [CALL_SET_REAL] = "fmiSetReal",
    [CALL_SET_INTEGER] = "fmiSetInteger",
    [CALL_SET_BOOLEAN] = "fmiSetBoolean",
    [CALL_DO_STEP] = "fmiDoStep",
};

/* The host's third argument: which standard's functions it serves. */
#define REMOTE_STANDARD_FMI2 "fmi2"
#define REMOTE_STANDARD_FMI1 "fmi1"

/* A request; `payload` bytes follow it:
 * - Instantiate: instance name, GUID and resource URI, each ended by '\0'; flag: visible,
 *   flag2: loggingOn, n: the fmi2Type.
 * - SetupExperiment: flag: toleranceDefined, a: tolerance, b: start, flag2: stopTimeDefined,
 *   c: stop. DoStep: a: t, b: h, flag: noSetFMUStatePriorToCurrentPoint; n value references
 *   to read with fmi2GetReal right after a successful step.
 * - Get<Type>: n value references. Set<Type>: n values, then n value references.
 * - Get/Set/FreeFMUstate, SerializedFMUstateSize: state (0 for a new one).
 *   SerializeFMUstate: state, n bytes wanted. DeSerializeFMUstate: state, n bytes of payload.
 * - GetDirectionalDerivative: n unknowns, n2 knowns; then n2 seed values, the unknowns and
 *   the knowns.
 * (Doubles come first, so every array of the payload is aligned.) */
typedef struct {
    uint32_t call;
    uint32_t flag;
    uint32_t flag2;
    uint32_t reserved;
    uint64_t n;
    uint64_t n2;
    uint64_t state; /* an fmi2FMUstate of the host, as a number the engine never dereferences */
    double a, b, c;
    uint64_t payload;
} remote_request;

typedef enum { REPLY_HELLO, REPLY_LOG, REPLY_RESULT } remote_reply_kind;

/* A reply; `payload` bytes follow it:
 * - LOG: status is the fmi2Status the FMU logged with; payload is the category and the
 *   formatted message, each ended by '\0'.
 * - RESULT: status is the call's fmi2Status (Instantiate: 0 or -1 for NULL); value is the
 *   state of Get/DeSerializeFMUstate, the size of SerializedFMUstateSize, or for DoStep the
 *   status of the fmi2GetReal after it (REMOTE_NOT_READ when the step failed); payload is what
 *   Get<Type>, SerializeFMUstate, GetDirectionalDerivative or DoStep's fmi2GetReal wrote. */
typedef struct {
    uint32_t kind;
    int32_t status;
    uint64_t value;
    uint64_t payload;
} remote_reply;

#define REMOTE_NOT_READ UINT64_MAX

/* An fmi2FMUstate of the host crosses the socket as a number. The engine hands it back
 * unchanged and only compares it: it stands for the state without being dereferenced. */
static inline uint64_t state_number(void *state)
{
    return (uint64_t)(uintptr_t)state;
}

static inline void *state_pointer(uint64_t number)
{
    return (void *)(uintptr_t)number;
}

/* The descriptor the host finds its socket on. */
#define REMOTE_SOCKET_FD 3

#endif
