/* Events a component handles inside its own step: an FMI 3.0 FMU's events, handled in event mode
 * after it returned early, and a Model Exchange FMU's state, time and step events, handled by the
 * engine's integrator. No rollback finds them: the component knows their time. A step may still
 * be undone (the master's localization trials, rollbacks and probes), so a reported event stays
 * pending with its component until the master accepts the step it belongs to; a restore drops
 * the component's events after the restored time. The pending list is per component, so a
 * component stepped on a worker thread reports without sharing anything. */
#ifndef SSX_OWN_EVENTS_H
#define SSX_OWN_EVENTS_H

#include "component.h"

/* The component handled an event of its own at t during the step it is taking. */
int own_event_report(ssx_system *sys, ssx_component *c, ssx_own_event_kind kind, double t);
/* The same, of one of its clocks (ssx_event_record's clock: 1 + its index). */
int own_event_report_clock(ssx_system *sys, ssx_component *c, ssx_own_event_kind kind, int clock,
                           double t);
/* The component's state is back at t: its events after t did not happen. */
void own_events_drop_after(ssx_component *c, double t);
/* How many events the component holds pending. A step reports its events at or after its
 * start, each after those pending at the same time, so the ones pending before it stay first:
 * own_events_keep_first(c, n) with the count from before the step drops every event the step
 * reported, one at its start too. */
size_t own_events_pending_count(const ssx_component *c);
/* The events reported after the first n happened somewhere in the step that reported them at
 * its end (an FMU that cannot return early). */
void own_events_mark_at_step_end(ssx_component *c, size_t n);
void own_events_keep_first(ssx_component *c, size_t n);
/* The time of the earliest event any component holds pending (1), or 0 when none does. */
int own_events_earliest(const ssx_system *sys, double *t);
/* Told of each own event as it is committed, to record it (the recording is a room above the
 * components) and tell its listeners: 0, or -1 with the error set. A listener may report more
 * own events of its own at the commit's time: they are committed in the same pass. */
typedef int (*own_event_committed)(ssx_system *sys, const ssx_event_record *record, void *user);
/* The master accepted the system's state at t: every component's pending events up to t become
 * event records, in time order (component order within one time), at micro step 0, each
 * handed to `committed`. */
int own_events_commit(ssx_system *sys, double t, own_event_committed committed, void *user);
/* ssx_initialize: nothing is pending. */
void own_events_clear(ssx_system *sys);
void own_event_list_free(ssx_own_event_list *list);

#endif
