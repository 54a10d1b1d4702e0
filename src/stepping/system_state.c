/* The whole system's snapshot and restore (system_state.h). */
#include "system_state.h"

#include "component_calls.h"
#include "recording.h"

int system_snapshot(ssx_system *sys, int slot)
{
    for (int i = 0; i < sys->n_components; ++i) {
        if (component_snapshot(sys, sys->components[i], slot) != 0) {
            return -1;
        }
    }
    return 0;
}

int system_restore(ssx_system *sys, int slot, double t)
{
    for (int i = 0; i < sys->n_components; ++i) {
        if (component_restore(sys, sys->components[i], slot, t) != 0) {
            return -1;
        }
    }
    return record_state_restored(sys, t);
}
