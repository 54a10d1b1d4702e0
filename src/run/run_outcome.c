/* A run's outcome in one call (see ssx_get_run_outcome): made of the public accessors, so it
 * says nothing they do not. */
#include <stddef.h>

#include "syssimx_engine.h"

void ssx_get_run_outcome(ssx_system *sys, ssx_run_outcome *out)
{
    out->time = ssx_time(sys);
    out->n_events = ssx_event_count(sys);
    out->termination = ssx_get_termination(sys);
    ssx_get_statistics(sys, &out->statistics);
    out->history_length = ssx_history_length(sys);
    out->history = out->history_length > 0 ? ssx_history_retain(sys) : NULL;
    out->history_time = ssx_history_time(sys);
    out->history_micro = ssx_history_micro(sys);
}
