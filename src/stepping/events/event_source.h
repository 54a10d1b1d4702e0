/* One concept for every event: a source fires at (t, micro) and the listeners subscribed to it
 * react (ssx_subscribe). A source is a master event indicator (located by the hybrid
 * algorithm, hybrid.c) or a component's own events (handled inside its step, own_events.h);
 * FMI 3.0 clocks would be one more kind. Listeners are called in one defined order: at a
 * communication point, own events first, in time order, then the located indicators; for one
 * firing, listeners in component order, each once with every source of that firing it
 * subscribed to. */
#ifndef SSX_EVENT_SOURCE_H
#define SSX_EVENT_SOURCE_H

#include "system.h"

/* The indicators marked in fired[] (per indicator, nonzero: fired) reach their listeners at the
 * event time t; scratch holds n_indicators ints. */
int event_sources_notify_indicators(ssx_system *sys, const int *fired, int *scratch, double t);
/* The master accepted the system's state at t: the components' own events up to t are
 * recorded and reach their listeners (own_events_commit), and the coupling settles after
 * a listener ran. */
int event_sources_commit_own(ssx_system *sys, double t);

#endif
