/* What a run keeps: the observers the time loop reports to (observer.h) and the event records.
 *
 * Two lists of observers. The kept samples go to the history (unless it is switched off) and
 * then to the observers added (ssx_add_observer: a file being written, a user's callbacks):
 * with an output interval above 1 (the system's or the run's) the recording keeps every k-th
 * communication point, the last point of each run and every sample off the grid, so all of
 * them see the same samples. Every sample, kept or not, goes to the observers of every sample
 * (the components' record hooks). */
#ifndef SSX_RECORDING_H
#define SSX_RECORDING_H

#include "history.h"
#include "observer.h"

/* Records every sample it is given into the history. */
typedef struct {
    ssx_observer base;
    ssx_history history;
    double **output_views; /* per component: its outputs array */
} ssx_history_observer;

/* Which communication points are kept: every k-th (counted from t0, which is the 0th), the
 * last point of each run, and every sample off the grid (event instants, trials): an event is
 * never decimated away. A run with an interval of its own counts from its start instead. */
typedef struct {
    int interval;
    int run_interval; /* 0: the current run keeps every interval-th point since ssx_initialize */
    long grid_points; /* seen since ssx_initialize */
    long run_points;  /* seen since the current run's start, which is the 0th */
} ssx_decimator;

typedef struct {
    ssx_observer **items;
    int n;
    size_t capacity;
} observer_list;

typedef struct ssx_recording {
    ssx_history_observer history;
    int history_off; /* ssx_set_history(sys, 0) */
    ssx_decimator decimator;
    observer_list kept;  /* the history (first, unless off) and the observers added */
    observer_list every; /* observers of every sample */
    int next_id;         /* of the next observer added */
    int output_interval;
    int run_output_interval; /* ssx_set_run_output_interval: 0, or each run's own */
    double run_end_time;     /* tf of the current ssx_run */

    ssx_event_record *events;
    size_t n_events;
    size_t events_capacity;
} ssx_recording;

/* NULL when out of memory. */
ssx_recording *recording_new(int output_interval);
void recording_free(ssx_recording *r);
/* Adds an observer of the kept samples, which the recording owns from now on (even when this
 * fails). Returns its id, or -1 when out of memory. */
int recording_add_observer(ssx_recording *r, ssx_observer *observer);
/* Removes (and releases) the observer of that id: 0, or -1 when there is none. */
int recording_remove_observer(ssx_recording *r, int id);
/* Adds an observer of every sample, which the recording owns: 0, or -1 when out of memory. */
int recording_add_sample_observer(ssx_recording *r, ssx_observer *observer);
/* Whether the history keeps samples (1, the default) or not (ssx_set_history): switched off,
 * from the next run on; on again, from the next start. */
void recording_keep_history(ssx_recording *r, int keep);

/* ssx_initialize: drops the last run's events and starts the observers. */
int recording_start(ssx_system *sys);
int recording_run_start(ssx_system *sys, size_t n_steps, double tf);
void recording_run_end(ssx_system *sys);
/* The system completed the communication point t. */
int record_grid_point(ssx_system *sys, double t);
/* The system completed (t, micro) off the grid: an event instant, or a trial (micro -1). */
int record_sample(ssx_system *sys, double t, int micro);
int record_state_restored(ssx_system *sys, double t);
int record_event(ssx_system *sys, const ssx_event_record *record);

#endif
