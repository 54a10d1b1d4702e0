/* What a run keeps: the observers the time loop reports to (observer.h) and the event records.
 * The history is always observed; with an output interval above 1 (the system's or the run's)
 * a decimator stands in front of it; the components' record hooks are a third observer, present only when one is set. */
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

/* Passes on every k-th communication point (counted from t0, which is the 0th), the last point
 * of each run, and every sample off the grid (event instants, trials): an event is never
 * decimated away. A run with an interval of its own counts from its start instead. */
typedef struct {
    ssx_observer base;
    ssx_observer *next;
    int interval;
    int run_interval; /* 0: the current run keeps every interval-th point since ssx_initialize */
    long grid_points; /* seen since ssx_initialize */
    long run_points;  /* seen since the current run's start, which is the 0th */
} ssx_decimator;

/* the history or its decimator, and the record hooks; a new kind of observer adds one */
enum { RECORDING_MAX_OBSERVERS = 3 };

typedef struct {
    ssx_history_observer history;
    ssx_decimator decimator;
    ssx_observer record_hooks;
    ssx_observer *observers[RECORDING_MAX_OBSERVERS];
    int n_observers;
    int output_interval;
    int run_output_interval; /* ssx_set_run_output_interval: 0, or each run's own */
    double run_end_time;     /* tf of the current ssx_run */

    ssx_event_record *events;
    size_t n_events;
    size_t events_capacity;
} ssx_recording;

void recording_init(ssx_recording *r, int output_interval);
void recording_free(ssx_recording *r);
/* ssx_initialize: drops the last run's events, chooses the observers and starts them. */
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
