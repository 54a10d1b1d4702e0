/* Subscriptions to event sources and the calls of their listeners (event_source.h). */
#include "event_source.h"

#include <math.h>

#include "array.h"
#include "component_calls.h"
#include "coupling.h"
#include "error.h"
#include "own_events.h"

/* How a listener's hook names a component's own events among the indicators it receives. */
static int own_events_name(int component)
{
    return -1 - component;
}

static int subscribed(const ssx_system *sys, ssx_event_source_kind kind, int index, int listener)
{
    for (int k = 0; k < sys->n_subscriptions; ++k) {
        const event_subscription *s = &sys->subscriptions[k];
        if (s->kind == kind && s->index == index && s->listener == listener) {
            return 1;
        }
    }
    return 0;
}

int ssx_subscribe(ssx_system *sys, ssx_event_source_kind kind, int index, int listener_component)
{
    if (kind == SSX_SOURCE_INDICATOR) {
        if (index < 0 || index >= sys->n_indicators) {
            return fail_config(sys, -1, index, NAN,
                               "unknown indicator index %d (system '%s' has %d)", index,
                               sys->name, sys->n_indicators);
        }
    } else if (kind == SSX_SOURCE_OWN_EVENTS) {
        if (system_component(sys, index) == NULL) {
            return -1;
        }
    } else {
        return fail_config(sys, -1, -1, NAN, "system '%s': unknown event source kind %d",
                           sys->name, (int)kind);
    }
    if (system_component(sys, listener_component) == NULL) {
        return -1;
    }
    if (subscribed(sys, kind, index, listener_component)) {
        return 0; /* an event reaches a listener once */
    }
    if (array_reserve((void **)&sys->subscriptions, &sys->subscriptions_capacity,
                      (size_t)sys->n_subscriptions + 1, sizeof *sys->subscriptions, 8) != 0) {
        return fail_config(sys, -1, -1, NAN, "out of memory subscribing to an event source");
    }
    sys->subscriptions[sys->n_subscriptions++] =
        (event_subscription){.kind = kind, .index = index, .listener = listener_component};
    return 0;
}

int ssx_add_event_connection(ssx_system *sys, int indicator, int listener_component)
{
    return ssx_subscribe(sys, SSX_SOURCE_INDICATOR, indicator, listener_component);
}

int event_sources_notify_indicators(ssx_system *sys, const int *fired, int *scratch, double t)
{
    if (sys->n_subscriptions == 0) {
        return 0;
    }
    for (int c = 0; c < sys->n_components; ++c) {
        int n = 0;
        for (int i = 0; i < sys->n_indicators; ++i) {
            if (fired[i] && subscribed(sys, SSX_SOURCE_INDICATOR, i, c)) {
                scratch[n++] = i;
            }
        }
        if (n > 0 && component_handle_events(sys, sys->components[c], scratch, n, t, t) != 0) {
            return -1;
        }
    }
    return 0;
}

typedef struct {
    double t;     /* where the system stands: the communication point that commits */
    int listened; /* a listener ran */
} commit_work;

/* One own event of `component` at t_event reaches its listeners. */
static int committed_to_listeners(ssx_system *sys, int component, double t_event, void *user)
{
    commit_work *w = user;
    int source = own_events_name(component);
    for (int c = 0; c < sys->n_components; ++c) {
        if (subscribed(sys, SSX_SOURCE_OWN_EVENTS, component, c)) {
            w->listened = 1;
            if (component_handle_events(sys, sys->components[c], &source, 1, t_event, w->t) !=
                0) {
                return -1;
            }
        }
    }
    return 0;
}

int event_sources_commit_own(ssx_system *sys, double t)
{
    if (sys->n_subscriptions == 0) {
        return own_events_commit(sys, t, NULL, NULL);
    }
    commit_work w = {.t = t, .listened = 0};
    /* the listeners see the system where it stands (ssx_time), whatever the caller sets after */
    double before = sys->time;
    sys->time = t;
    int status = own_events_commit(sys, t, committed_to_listeners, &w);
    sys->time = before;
    if (status != 0) {
        return -1;
    }
    return w.listened ? coupling_settle(sys, t) : 0;
}
