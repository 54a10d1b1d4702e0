/* One concept for every event: a source fires at (t, micro) and the listeners subscribed to it
 * react (ssx_subscribe). A source is a master event indicator (located by the hybrid
 * algorithm, hybrid.c), a component's own events (handled inside its step, own_events.h) or
 * an FMI 3.0 output clock (a kind of own event). A listener is a component's hook, or a
 * triggered input clock of an FMI 3.0 FMU that the source ticks (ssx_connect_clock).
 * Listeners are called in one defined order: at a communication point, own events first, in
 * time order, then the located indicators; for one firing, the clocks it ticks in the order
 * they were connected, then the hooks in component order, each once with every source of that
 * firing it subscribed to. */
#ifndef SSX_EVENT_SOURCE_H
#define SSX_EVENT_SOURCE_H

#include "system.h"

/* Each kind's name by its ssx_event_source_kind, as a plan writes it, then NULL. */
extern const char *const event_source_names[];
/* Frees the subscriptions and the sources' own data (with the system). */
void event_sources_free(ssx_system *sys);

/* The indicators marked in fired[] (per indicator, nonzero: fired) reach their listeners at the
 * event time t; scratch holds n_indicators ints. */
int event_sources_notify_indicators(ssx_system *sys, const int *fired, int *scratch, double t);
/* The master accepted the system's state at t: the components' own events up to t are
 * recorded and reach their listeners (own_events_commit), and the coupling settles after
 * a listener ran. */
int event_sources_commit_own(ssx_system *sys, double t);
/* Whether the system locates its output clocks' ticks (hybrid.c): a listener waits for one and
 * every component can roll back. */
int event_sources_locate_ticks(const ssx_system *sys);
/* The earliest pending tick of an output clock with a listener into *t; 0 when none.
 * *at_step_end: that tick was reported at the end of the step that held it (its FMU cannot
 * return early), not at its own time. */
int event_sources_earliest_tick(const ssx_system *sys, double *t, int *at_step_end);

#endif
