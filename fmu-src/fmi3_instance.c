/* The FMI 3.0 instance's state machine (which mode it is in, refusing a call in the wrong one)
 * and its status mapping; see fmi3_instance.h. */
#include "fmi3_instance.h"

#include "fmu_log.h"

static const char *const mode_names[] = {
    "Instantiated", "Initialization Mode",  "Event Mode",
    "Step Mode",    "Continuous-Time Mode", "Terminated",
    "the fatal state (after fmi3Fatal)"};

fmi3_mode fmi3_mode_of(const fmu_instance *inst)
{
    switch (inst->phase) {
    case PHASE_INSTANTIATED: return MODE_INSTANTIATED;
    case PHASE_INITIALIZATION: return MODE_INITIALIZATION;
    case PHASE_STEP: return inst->in_event_mode ? MODE_EVENT : MODE_STEP;
    case PHASE_TERMINATED: return MODE_TERMINATED;
    case PHASE_EVENT: return MODE_EVENT;
    case PHASE_CONTINUOUS_TIME: return MODE_CONTINUOUS_TIME;
    case PHASE_FATAL: break;
    }
    return MODE_FATAL;
}

const char *fmi3_mode_name(fmi3_mode mode)
{
    return mode_names[mode];
}

fmi3_instance *fmi3_refuse_in_mode(fmi3_instance *inst, const char *function)
{
    fmu_error(&inst->core, "%s is not allowed in %s", function,
              fmi3_mode_name(fmi3_mode_of(&inst->core)));
    return NULL;
}

fmi3Status fmi3_status(fmu_status status)
{
    switch (status) {
    case FMU_OK: return fmi3OK;
    case FMU_WARNING: return fmi3Warning;
    case FMU_DISCARD: return fmi3Discard;
    case FMU_ERROR: break;
    case FMU_FATAL: return fmi3Fatal;
    }
    return fmi3Error;
}
