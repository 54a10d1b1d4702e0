/* Subscriptions to event sources and the calls of their listeners (event_source.h). */
#include "event_source.h"

#include <math.h>
#include <stdlib.h>

#include "array.h"
#include "component_calls.h"
#include "coupling.h"
#include "error.h"
#include "fmu_binding.h"
#include "own_events.h"
#include "recording.h"

/* A listener subscribed to an event source. */
typedef struct {
    ssx_event_source_kind kind;
    int index; /* the indicator's, the component's whose own events, the output clock's */
    int listener;
    int tick; /* a clock connection: the listener's triggered clock it ticks; -1: its hook */
} event_subscription;

/* An output clock as an event source (ssx_add_output_clock_source). */
typedef struct {
    int component;
    int clock;
} output_clock_source;

/* The system's subscriptions, and what a kind of source keeps of its own. */
struct event_sources {
    event_subscription *subscriptions;
    int n_subscriptions;
    size_t subscriptions_capacity;
    output_clock_source *output_clock_sources;
    int n_output_clock_sources;
    size_t output_clock_sources_capacity;
};

const char *const event_source_names[] = {
    [SSX_SOURCE_INDICATOR] = "indicator",
    [SSX_SOURCE_OWN_EVENTS] = "own_events",
    [SSX_SOURCE_OUTPUT_CLOCK] = "output_clock",
    NULL,
};

/* The system's event sources to read: none subscribed or added yet reads as empty. */
static const struct event_sources *sources(const ssx_system *sys)
{
    static const struct event_sources none = {0};
    return sys->event_sources != NULL ? sys->event_sources : &none;
}

/* The system's event sources to change, made at the first change; NULL (the error set) when
 * out of memory. */
static struct event_sources *sources_to_change(ssx_system *sys, const char *doing)
{
    if (sys->event_sources == NULL) {
        sys->event_sources = calloc(1, sizeof *sys->event_sources);
        if (sys->event_sources == NULL) {
            fail_config(sys, -1, -1, NAN, "out of memory %s", doing);
        }
    }
    return sys->event_sources;
}

void event_sources_free(ssx_system *sys)
{
    if (sys->event_sources != NULL) {
        free(sys->event_sources->subscriptions);
        free(sys->event_sources->output_clock_sources);
        free(sys->event_sources);
        sys->event_sources = NULL;
    }
}

/* How a listener's hook names a component's own events among the indicators it receives. */
static int own_events_name(int component)
{
    return -1 - component;
}

/* How a listener's hook names an output clock source. */
static int output_clock_name(const ssx_system *sys, int source)
{
    return -1 - sys->n_components - source;
}

/* Whether the listener's hook (tick < 0) or its triggered clock `tick` is subscribed. */
static int subscribed_as(const ssx_system *sys, ssx_event_source_kind kind, int index,
                         int listener, int tick)
{
    const struct event_sources *e = sources(sys);
    for (int k = 0; k < e->n_subscriptions; ++k) {
        const event_subscription *s = &e->subscriptions[k];
        if (s->kind == kind && s->index == index && s->listener == listener && s->tick == tick) {
            return 1;
        }
    }
    return 0;
}

static int subscribed(const ssx_system *sys, ssx_event_source_kind kind, int index, int listener)
{
    return subscribed_as(sys, kind, index, listener, -1);
}

static int add_subscription(ssx_system *sys, ssx_event_source_kind kind, int index, int listener,
                            int tick)
{
    if (subscribed_as(sys, kind, index, listener, tick)) {
        return 0; /* an event reaches a listener once */
    }
    const char *doing = "subscribing to an event source";
    struct event_sources *e = sources_to_change(sys, doing);
    if (e == NULL) {
        return -1;
    }
    if (array_reserve((void **)&e->subscriptions, &e->subscriptions_capacity,
                      (size_t)e->n_subscriptions + 1, sizeof *e->subscriptions, 8) != 0) {
        return fail_config(sys, -1, -1, NAN, "out of memory %s", doing);
    }
    e->subscriptions[e->n_subscriptions++] = (event_subscription){
        .kind = kind, .index = index, .listener = listener, .tick = tick};
    return 0;
}

/* The clock counts of an FMU component's binding; -1 (the error set) for another kind, and
 * where `ticked` for a kind that ticks no triggered clock (a Scheduled Execution component's
 * output clocks are sources all the same). */
static int clock_counts(ssx_system *sys, int component, const char *what, int ticked,
                        size_t *n_output, size_t *n_triggered)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    ssx_fmu *fmu = c->ops->fmu != NULL ? c->ops->fmu(c) : NULL;
    if (fmu == NULL || (ticked && c->ops->tick_triggered_clock == NULL)) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s' is no FMI 3.0 Co-Simulation FMU: it has no %s",
                           c->name, what);
    }
    ssx_fmu_clock_counts(fmu, n_output, n_triggered);
    return 0;
}

int ssx_add_output_clock_source(ssx_system *sys, int component, int clock)
{
    size_t n_output = 0, n_triggered = 0;
    if (clock_counts(sys, component, "output clocks", 0, &n_output, &n_triggered) != 0) {
        return -1;
    }
    if (clock < 0 || (size_t)clock >= n_output) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s': unknown output clock %d (it has %zu)",
                           sys->components[component]->name, clock, n_output);
    }
    const struct event_sources *known = sources(sys);
    for (int s = 0; s < known->n_output_clock_sources; ++s) {
        const output_clock_source *source = &known->output_clock_sources[s];
        if (source->component == component && source->clock == clock) {
            return s;
        }
    }
    const char *doing = "adding an output clock source";
    struct event_sources *e = sources_to_change(sys, doing);
    if (e == NULL) {
        return -1;
    }
    if (array_reserve((void **)&e->output_clock_sources, &e->output_clock_sources_capacity,
                      (size_t)e->n_output_clock_sources + 1, sizeof *e->output_clock_sources,
                      4) != 0) {
        return fail_config(sys, -1, -1, NAN, "out of memory %s", doing);
    }
    e->output_clock_sources[e->n_output_clock_sources] =
        (output_clock_source){.component = component, .clock = clock};
    return e->n_output_clock_sources++;
}

/* The triggered clock `clock` of component `listener` ticks at t, sampling its drivers' outputs
 * there. */
static int tick_clock(ssx_system *sys, int listener, int clock, double t)
{
    ssx_component *c = sys->components[listener];
    coupling_propagate_inputs(sys, c);
    return c->ops->tick_triggered_clock(sys, c, clock, t);
}

/* Whether a source of that kind and index exists (else -1, the error set). */
static int check_source(ssx_system *sys, ssx_event_source_kind kind, int index)
{
    if (kind == SSX_SOURCE_INDICATOR) {
        if (index < 0 || index >= sys->n_indicators) {
            return fail_config(sys, -1, index, NAN,
                               "unknown indicator index %d (system '%s' has %d)", index,
                               sys->name, sys->n_indicators);
        }
        return 0;
    }
    if (kind == SSX_SOURCE_OWN_EVENTS) {
        return system_component(sys, index) == NULL ? -1 : 0;
    }
    if (kind == SSX_SOURCE_OUTPUT_CLOCK) {
        int n = sources(sys)->n_output_clock_sources;
        if (index < 0 || index >= n) {
            return fail_config(sys, -1, -1, NAN,
                               "unknown output clock source %d (system '%s' has %d)", index,
                               sys->name, n);
        }
        return 0;
    }
    return fail_config(sys, -1, -1, NAN, "system '%s': unknown event source kind %d", sys->name,
                       (int)kind);
}

int ssx_connect_clock(ssx_system *sys, ssx_event_source_kind kind, int index,
                      int listener_component, int clock)
{
    size_t n_output = 0, n_triggered = 0;
    if (check_source(sys, kind, index) != 0 ||
        clock_counts(sys, listener_component, "triggered input clocks", 1, &n_output,
                     &n_triggered) != 0) {
        return -1;
    }
    if (kind == SSX_SOURCE_OWN_EVENTS) {
        return fail_config(sys, listener_component, -1, NAN,
                           "a clock ticks on an indicator or an output clock, not on all of a "
                           "component's own events");
    }
    if (clock < 0 || (size_t)clock >= n_triggered) {
        return fail_config(sys, listener_component, -1, NAN,
                           "component '%s': unknown triggered input clock %d (it has %zu)",
                           sys->components[listener_component]->name, clock, n_triggered);
    }
    return add_subscription(sys, kind, index, listener_component, clock);
}

int ssx_subscribe(ssx_system *sys, ssx_event_source_kind kind, int index, int listener_component)
{
    if (check_source(sys, kind, index) != 0 ||
        system_component(sys, listener_component) == NULL) {
        return -1;
    }
    return add_subscription(sys, kind, index, listener_component, -1);
}

int ssx_add_event_connection(ssx_system *sys, int indicator, int listener_component)
{
    return ssx_subscribe(sys, SSX_SOURCE_INDICATOR, indicator, listener_component);
}

int event_sources_notify_indicators(ssx_system *sys, const int *fired, int *scratch, double t)
{
    const struct event_sources *e = sources(sys);
    if (e->n_subscriptions == 0) {
        return 0;
    }
    /* the clocks the indicators tick first, in the order they were connected: they sample the
     * values at the crossing */
    for (int k = 0; k < e->n_subscriptions; ++k) {
        const event_subscription *s = &e->subscriptions[k];
        if (s->kind == SSX_SOURCE_INDICATOR && s->tick >= 0 && fired[s->index] &&
            tick_clock(sys, s->listener, s->tick, t) != 0) {
            return -1;
        }
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

/* The number of the output clock source of a component's output clock tick (`clock`: 1 + the
 * clock's index, as own events number it), -1 when it is no source. */
static int output_clock_source_of(const ssx_system *sys, int component, int clock)
{
    const struct event_sources *e = sources(sys);
    for (int s = 0; s < e->n_output_clock_sources; ++s) {
        const output_clock_source *source = &e->output_clock_sources[s];
        if (source->component == component && source->clock + 1 == clock) {
            return s;
        }
    }
    return -1;
}

/* Whether a clock is connected to the output clock source or a hook subscribed to it. */
static int source_listened(const struct event_sources *e, int source)
{
    for (int k = 0; k < e->n_subscriptions; ++k) {
        if (e->subscriptions[k].kind == SSX_SOURCE_OUTPUT_CLOCK &&
            e->subscriptions[k].index == source) {
            return 1;
        }
    }
    return 0;
}

int event_sources_locate_ticks(const ssx_system *sys)
{
    const struct event_sources *e = sources(sys);
    int listened = 0;
    for (int s = 0; s < e->n_output_clock_sources && !listened; ++s) {
        listened = source_listened(e, s);
    }
    for (int i = 0; listened && i < sys->n_components; ++i) {
        listened = component_can_roll_back(sys->components[i]);
    }
    return listened;
}

int event_sources_earliest_tick(const ssx_system *sys, double *t, int *at_step_end)
{
    *at_step_end = 0;
    const struct event_sources *e = sources(sys);
    /* asked after every piece: most systems have no output clock source at all */
    if (e->n_output_clock_sources == 0 ||
        !atomic_load_explicit(&sys->own_events_pending, memory_order_relaxed)) {
        return 0;
    }
    int found = 0;
    for (int c = 0; c < sys->n_components; ++c) {
        const ssx_own_event_list *list = &sys->components[c]->own_events;
        /* pending in time order: the component's first listened tick is its earliest */
        for (size_t k = 0; k < list->n; ++k) {
            const ssx_own_event *tick = &list->pending[k];
            if (tick->kind != SSX_OWN_OUTPUT_CLOCK) {
                continue;
            }
            int source = output_clock_source_of(sys, c, tick->clock);
            if (source >= 0 && source_listened(e, source)) {
                if (!found || tick->t < *t) {
                    *t = tick->t;
                    *at_step_end = tick->at_step_end;
                } else if (tick->t == *t) {
                    *at_step_end |= tick->at_step_end;
                }
                found = 1;
                break;
            }
        }
    }
    return found;
}

/* An output clock's tick ticks the clocks connected to it (connection order), then reaches
 * the hooks subscribed to it (component order), where the system stands. */
static int tick_to_listeners(ssx_system *sys, const ssx_event_record *record, commit_work *w)
{
    int source = output_clock_source_of(sys, record->component, record->clock);
    if (source < 0) {
        return 0;
    }
    const struct event_sources *e = sources(sys);
    for (int k = 0; k < e->n_subscriptions; ++k) {
        const event_subscription *s = &e->subscriptions[k];
        if (s->kind == SSX_SOURCE_OUTPUT_CLOCK && s->index == source && s->tick >= 0) {
            w->listened = 1;
            if (tick_clock(sys, s->listener, s->tick, w->t) != 0) {
                return -1;
            }
        }
    }
    int name = output_clock_name(sys, source);
    for (int c = 0; c < sys->n_components; ++c) {
        if (subscribed(sys, SSX_SOURCE_OUTPUT_CLOCK, source, c)) {
            w->listened = 1;
            if (component_handle_events(sys, sys->components[c], &name, 1, record->t, w->t) !=
                0) {
                return -1;
            }
        }
    }
    return 0;
}

/* One own event is recorded. */
static int committed_to_recording(ssx_system *sys, const ssx_event_record *record, void *user)
{
    (void)user;
    return record_event(sys, record);
}

/* One own event is recorded and reaches its listeners: an output clock's tick those of the
 * clock, any other those of the component's own events. */
static int committed_to_listeners(ssx_system *sys, const ssx_event_record *record, void *user)
{
    commit_work *w = user;
    if (record_event(sys, record) != 0) {
        return -1;
    }
    if (record->own == SSX_OWN_OUTPUT_CLOCK) {
        return tick_to_listeners(sys, record, w);
    }
    int source = own_events_name(record->component);
    for (int c = 0; c < sys->n_components; ++c) {
        if (subscribed(sys, SSX_SOURCE_OWN_EVENTS, record->component, c)) {
            w->listened = 1;
            if (component_handle_events(sys, sys->components[c], &source, 1, record->t, w->t) !=
                0) {
                return -1;
            }
        }
    }
    return 0;
}

int event_sources_commit_own(ssx_system *sys, double t)
{
    if (sources(sys)->n_subscriptions == 0) {
        return own_events_commit(sys, t, committed_to_recording, NULL);
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
