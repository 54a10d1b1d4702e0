/* fmi2Get/Set/Free/Serialize/DeSerializeFMUstate. A state is the time, the phase, every
 * variable value, the continuous states and the event indicators Model Exchange compares with;
 * a back-end restarts its integration after a set. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_instance.h"
#include "fmu_log.h"
#include "fmu_solver.h"

/* The header is also the serialized form's header; the GUID rejects another model's bytes. */
typedef struct {
    char guid[40];
    uint64_t n_values;
    uint64_t n_states;
    int64_t phase;
    double time;
} state_header;

typedef struct {
    state_header header;
    double data[]; /* n_values variable values, n_states states, then the previous indicators */
} fmu_snapshot;

static size_t data_count(const fmu_instance *inst)
{
    return inst->n_variables + inst->model->n_states + inst->model->n_event_indicators;
}

static int matches(const fmu_instance *inst, const state_header *header)
{
    if (!(header->phase >= PHASE_INSTANTIATED && header->phase <= PHASE_TERMINATED))
        return 0;
    /* a state taken while running belongs to the interface (step or event mode) it ran in */
    fmu_phase phase = (fmu_phase)header->phase;
    int running = (PHASE_BIT(phase) & PHASES_RUNNING) != 0;
    if (running && (phase == PHASE_STEP) != (inst->running_phase == PHASE_STEP))
        return 0;
    return strncmp(header->guid, inst->guid, sizeof header->guid) == 0 &&
           header->n_values == inst->n_variables && header->n_states == inst->model->n_states;
}

static void capture(const fmu_instance *inst, fmu_snapshot *snapshot)
{
    memset(&snapshot->header, 0, sizeof snapshot->header);
    memcpy(snapshot->header.guid, inst->guid, sizeof inst->guid);
    snapshot->header.n_values = inst->n_variables;
    snapshot->header.n_states = inst->model->n_states;
    snapshot->header.phase = inst->phase;
    snapshot->header.time = inst->time;
    memcpy(snapshot->data, inst->values, inst->n_variables * sizeof(double));
    memcpy(snapshot->data + inst->n_variables, inst->x, inst->model->n_states * sizeof(double));
    memcpy(snapshot->data + inst->n_variables + inst->model->n_states, inst->z_previous,
           inst->model->n_event_indicators * sizeof(double));
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmu_instance *inst = fmu_checked(c, "fmi2GetFMUstate", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    if (FMUstate == NULL)
        return fmu_error(inst, "fmi2GetFMUstate: the state pointer is NULL");
    fmu_snapshot *snapshot = *FMUstate;
    if (snapshot != NULL) {
        /* the master passes its previous state back to be overwritten: no allocation */
        if (!matches(inst, &snapshot->header))
            return fmu_error(inst, "fmi2GetFMUstate: the state to reuse is not a state of "
                                   "this FMU");
    } else {
        snapshot = malloc(sizeof *snapshot + data_count(inst) * sizeof(double));
        if (snapshot == NULL)
            return fmu_error(inst, "fmi2GetFMUstate: out of memory");
    }
    capture(inst, snapshot);
    *FMUstate = snapshot;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    fmu_instance *inst = fmu_checked(c, "fmi2SetFMUstate", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    const fmu_snapshot *snapshot = FMUstate;
    if (snapshot == NULL || !matches(inst, &snapshot->header))
        return fmu_error(inst, "fmi2SetFMUstate: the state is NULL or not a state of this FMU");
    inst->phase = (fmu_phase)snapshot->header.phase;
    inst->time = snapshot->header.time;
    memcpy(inst->values, snapshot->data, inst->n_variables * sizeof(double));
    memcpy(inst->x, snapshot->data + inst->n_variables, inst->model->n_states * sizeof(double));
    memcpy(inst->z_previous, snapshot->data + inst->n_variables + inst->model->n_states,
           inst->model->n_event_indicators * sizeof(double));
    inst->outputs_stale = 1;
    fmu_solver_invalidate(inst);
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    fmu_instance *inst = fmu_checked(c, "fmi2FreeFMUstate", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    if (FMUstate == NULL)
        return fmu_error(inst, "fmi2FreeFMUstate: the state pointer is NULL");
    free(*FMUstate);
    *FMUstate = NULL;
    return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    fmu_instance *inst = fmu_checked(c, "fmi2SerializedFMUstateSize", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    const fmu_snapshot *snapshot = FMUstate;
    if (snapshot == NULL || size == NULL || !matches(inst, &snapshot->header))
        return fmu_error(inst, "fmi2SerializedFMUstateSize: invalid state or size pointer");
    *size = sizeof(state_header) + data_count(inst) * sizeof(double);
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[],
                                 size_t size)
{
    fmu_instance *inst = fmu_checked(c, "fmi2SerializeFMUstate", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    const fmu_snapshot *snapshot = FMUstate;
    size_t needed = sizeof(state_header) + data_count(inst) * sizeof(double);
    if (snapshot == NULL || serializedState == NULL || !matches(inst, &snapshot->header))
        return fmu_error(inst, "fmi2SerializeFMUstate: invalid state or buffer");
    if (size != needed)
        return fmu_error(inst, "fmi2SerializeFMUstate: buffer of %zu bytes, %zu needed", size,
                         needed);
    memcpy(serializedState, &snapshot->header, sizeof(state_header));
    memcpy(serializedState + sizeof(state_header), snapshot->data,
           data_count(inst) * sizeof(double));
    return fmi2OK;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate)
{
    fmu_instance *inst = fmu_checked(c, "fmi2DeSerializeFMUstate", PHASES_ANY);
    if (inst == NULL)
        return fmi2Error;
    size_t needed = sizeof(state_header) + data_count(inst) * sizeof(double);
    if (serializedState == NULL || FMUstate == NULL || size != needed)
        return fmu_error(inst, "fmi2DeSerializeFMUstate: %zu bytes given, %zu expected", size,
                         needed);
    state_header header;
    memcpy(&header, serializedState, sizeof header);
    if (!matches(inst, &header))
        return fmu_error(inst, "fmi2DeSerializeFMUstate: the bytes are not a state of this FMU");
    fmu_snapshot *snapshot = *FMUstate;
    if (snapshot != NULL && !matches(inst, &snapshot->header))
        return fmu_error(inst, "fmi2DeSerializeFMUstate: the state to reuse is not a state of "
                               "this FMU");
    if (snapshot == NULL) {
        snapshot = malloc(sizeof *snapshot + data_count(inst) * sizeof(double));
        if (snapshot == NULL)
            return fmu_error(inst, "fmi2DeSerializeFMUstate: out of memory");
    }
    snapshot->header = header;
    memcpy(snapshot->data, serializedState + sizeof(state_header),
           data_count(inst) * sizeof(double));
    *FMUstate = snapshot;
    return fmi2OK;
}
