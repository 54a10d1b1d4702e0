/* FMU states for every interface's get/set/free/serialize/deserialize calls. A state is the
 * time, the phase, the event mode, every variable value, the continuous states, the event
 * indicators Model Exchange compares with and the event a step stopped at, if any; a back-end
 * restarts its integration after a set. */
#include "fmu_state.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_log.h"
#include "fmu_solver.h"

/* The header is also the serialized form's header; the GUID rejects another model's bytes. */
typedef struct {
    char guid[40];
    uint64_t n_values;
    uint64_t n_states;
    int64_t phase;
    int64_t in_event_mode;
    int64_t event_pending;
    double time;
} state_header;

typedef struct {
    state_header header;
    /* n_values variable values, n_states states, then per event indicator its previous value
     * (Model Exchange) and whether its event is pending */
    double data[];
} fmu_snapshot;

static size_t data_count(const fmu_instance *inst)
{
    return inst->n_variables + inst->model->n_states + 2 * inst->model->n_event_indicators;
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
    snapshot->header.in_event_mode = inst->in_event_mode;
    snapshot->header.event_pending = inst->event_pending;
    snapshot->header.time = inst->time;
    memcpy(snapshot->data, inst->values, inst->n_variables * sizeof(double));
    double *x = snapshot->data + inst->n_variables;
    memcpy(x, inst->x, inst->model->n_states * sizeof(double));
    double *z_previous = x + inst->model->n_states;
    memcpy(z_previous, inst->z_previous, inst->model->n_event_indicators * sizeof(double));
    double *fired = z_previous + inst->model->n_event_indicators;
    for (size_t i = 0; i < inst->model->n_event_indicators; ++i)
        fired[i] = inst->fired[i];
}

fmu_status fmu_state_get(fmu_instance *inst, const char *function, void **FMUstate)
{
    if (FMUstate == NULL)
        return fmu_error(inst, "%s: the state pointer is NULL", function);
    fmu_snapshot *snapshot = *FMUstate;
    if (snapshot != NULL) {
        /* the master passes its previous state back to be overwritten: no allocation */
        if (!matches(inst, &snapshot->header))
            return fmu_error(inst, "%s: the state to reuse is not a state of this FMU",
                             function);
    } else {
        snapshot = malloc(sizeof *snapshot + data_count(inst) * sizeof(double));
        if (snapshot == NULL)
            return fmu_error(inst, "%s: out of memory", function);
    }
    capture(inst, snapshot);
    *FMUstate = snapshot;
    return FMU_OK;
}

fmu_status fmu_state_set(fmu_instance *inst, const char *function, const void *FMUstate)
{
    const fmu_snapshot *snapshot = FMUstate;
    if (snapshot == NULL || !matches(inst, &snapshot->header))
        return fmu_error(inst, "%s: the state is NULL or not a state of this FMU", function);
    inst->phase = (fmu_phase)snapshot->header.phase;
    inst->in_event_mode = snapshot->header.in_event_mode != 0;
    inst->event_pending = snapshot->header.event_pending != 0;
    inst->time = snapshot->header.time;
    memcpy(inst->values, snapshot->data, inst->n_variables * sizeof(double));
    const double *x = snapshot->data + inst->n_variables;
    memcpy(inst->x, x, inst->model->n_states * sizeof(double));
    const double *z_previous = x + inst->model->n_states;
    memcpy(inst->z_previous, z_previous, inst->model->n_event_indicators * sizeof(double));
    const double *fired = z_previous + inst->model->n_event_indicators;
    for (size_t i = 0; i < inst->model->n_event_indicators; ++i)
        inst->fired[i] = fired[i] != 0.0;
    fmu_hold_inputs(inst);
    inst->outputs_stale = 1;
    fmu_solver_invalidate(inst);
    return FMU_OK;
}

fmu_status fmu_state_free(fmu_instance *inst, const char *function, void **FMUstate)
{
    if (FMUstate == NULL)
        return fmu_error(inst, "%s: the state pointer is NULL", function);
    free(*FMUstate);
    *FMUstate = NULL;
    return FMU_OK;
}

fmu_status fmu_state_serialized_size(fmu_instance *inst, const char *function,
                                     const void *FMUstate, size_t *size)
{
    const fmu_snapshot *snapshot = FMUstate;
    if (snapshot == NULL || size == NULL || !matches(inst, &snapshot->header))
        return fmu_error(inst, "%s: invalid state or size pointer", function);
    *size = sizeof(state_header) + data_count(inst) * sizeof(double);
    return FMU_OK;
}

fmu_status fmu_state_serialize(fmu_instance *inst, const char *function, const void *FMUstate,
                               unsigned char serializedState[], size_t size)
{
    const fmu_snapshot *snapshot = FMUstate;
    size_t needed = sizeof(state_header) + data_count(inst) * sizeof(double);
    if (snapshot == NULL || serializedState == NULL || !matches(inst, &snapshot->header))
        return fmu_error(inst, "%s: invalid state or buffer", function);
    if (size != needed)
        return fmu_error(inst, "%s: buffer of %zu bytes, %zu needed", function, size, needed);
    memcpy(serializedState, &snapshot->header, sizeof(state_header));
    memcpy(serializedState + sizeof(state_header), snapshot->data,
           data_count(inst) * sizeof(double));
    return FMU_OK;
}

fmu_status fmu_state_deserialize(fmu_instance *inst, const char *function,
                                 const unsigned char serializedState[], size_t size,
                                 void **FMUstate)
{
    size_t needed = sizeof(state_header) + data_count(inst) * sizeof(double);
    if (serializedState == NULL || FMUstate == NULL || size != needed)
        return fmu_error(inst, "%s: %zu bytes given, %zu expected", function, size, needed);
    state_header header;
    memcpy(&header, serializedState, sizeof header);
    if (!matches(inst, &header))
        return fmu_error(inst, "%s: the bytes are not a state of this FMU", function);
    fmu_snapshot *snapshot = *FMUstate;
    if (snapshot != NULL && !matches(inst, &snapshot->header))
        return fmu_error(inst, "%s: the state to reuse is not a state of this FMU", function);
    if (snapshot == NULL) {
        snapshot = malloc(sizeof *snapshot + data_count(inst) * sizeof(double));
        if (snapshot == NULL)
            return fmu_error(inst, "%s: out of memory", function);
    }
    snapshot->header = header;
    memcpy(snapshot->data, serializedState + sizeof(state_header),
           data_count(inst) * sizeof(double));
    *FMUstate = snapshot;
    return FMU_OK;
}
