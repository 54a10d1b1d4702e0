/* The read-only accessors of a system's results: where it stands, its history, event records,
 * localization trials and statistics. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "recording.h"
#include "system.h"

double ssx_time(const ssx_system *sys)
{
    return sys->time;
}

const ssx_termination *ssx_get_termination(const ssx_system *sys)
{
    return sys != NULL ? &sys->termination : NULL;
}

/* The history observer's block: one every system has, decimated or not. */
static ssx_history_block *history_block(const ssx_system *sys)
{
    return sys->recording->history.history.block;
}

size_t ssx_history_length(const ssx_system *sys)
{
    return sys->recording->history.history.length;
}

const double *ssx_history_time(const ssx_system *sys)
{
    return history_block(sys) != NULL ? history_block(sys)->time.data : NULL;
}

const int *ssx_history_micro(const ssx_system *sys)
{
    return history_block(sys) != NULL ? history_block(sys)->micro.data : NULL;
}

const double *ssx_history_values(const ssx_system *sys, int component)
{
    const ssx_history_block *b = history_block(sys);
    if (b == NULL || component < 0 || component >= b->n_components) {
        return NULL;
    }
    return b->values[component];
}

size_t ssx_history_bytes(const ssx_system *sys)
{
    return history_bytes(&sys->recording->history.history);
}

ssx_history_block *ssx_history_retain(ssx_system *sys)
{
    return history_block(sys) != NULL ? history_block_retain(history_block(sys)) : NULL;
}

const double *ssx_history_block_values(const ssx_history_block *block, int component)
{
    if (block == NULL || component < 0 || component >= block->n_components) {
        return NULL;
    }
    return block->values[component];
}

void ssx_history_release(ssx_history_block *block)
{
    history_block_release(block);
}

size_t ssx_event_count(const ssx_system *sys)
{
    return sys->recording->n_events;
}

int ssx_event_get(const ssx_system *sys, size_t index, ssx_event_record *out)
{
    if (index >= sys->recording->n_events || out == NULL) {
        return -1;
    }
    *out = sys->recording->events[index];
    return 0;
}

size_t ssx_event_trial_count(const ssx_system *sys)
{
    return sys->localization.n_trials;
}

int ssx_event_trial(const ssx_system *sys, size_t index, ssx_localization_trial *out)
{
    if (index >= sys->localization.n_trials || out == NULL) {
        return -1;
    }
    *out = sys->localization.trials[index];
    return 0;
}

/* How many of n items from first lie below count. */
static size_t available(size_t first, size_t n, size_t count)
{
    return first >= count ? 0 : n < count - first ? n : count - first;
}

size_t ssx_events_copy(const ssx_system *sys, size_t first, size_t n, ssx_event_record *out)
{
    size_t copied = out != NULL ? available(first, n, sys->recording->n_events) : 0;
    if (copied > 0) {
        memcpy(out, sys->recording->events + first, copied * sizeof *out);
    }
    return copied;
}

size_t ssx_event_trials_copy(const ssx_system *sys, size_t first, size_t n,
                             ssx_localization_trial *out)
{
    size_t copied = out != NULL ? available(first, n, sys->localization.n_trials) : 0;
    if (copied > 0) {
        memcpy(out, sys->localization.trials + first, copied * sizeof *out);
    }
    return copied;
}

void ssx_get_statistics(const ssx_system *sys, ssx_statistics *out)
{
    if (out != NULL) {
        *out = sys->stats;
    }
}
