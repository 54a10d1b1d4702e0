/* Pending own events per component, committed in time order when the master accepts a step. */
#include "own_events.h"

#include <math.h>
#include <stdlib.h>

#include "array.h"
#include "component.h"
#include "error.h"
#include "system.h"

int own_event_report(ssx_system *sys, ssx_component *c, ssx_own_event_kind kind, double t)
{
    return own_event_report_clock(sys, c, kind, 0, t);
}

int own_event_report_clock(ssx_system *sys, ssx_component *c, ssx_own_event_kind kind, int clock,
                           double t)
{
    ssx_own_event_list *list = &c->own_events;
    if (array_reserve((void **)&list->pending, &list->capacity, list->n + 1,
                      sizeof *list->pending, 4) != 0) {
        return fail(sys, c->index, -1, t, "component '%s': out of memory recording its event "
                    "at t=%.17g", c->name, t);
    }
    /* a component reports in time order; keep the list sorted even if it does not */
    size_t at = list->n;
    while (at > 0 && list->pending[at - 1].t > t) {
        list->pending[at] = list->pending[at - 1];
        --at;
    }
    list->pending[at] = (ssx_own_event){.t = t, .kind = kind, .clock = clock};
    list->n++;
    atomic_store_explicit(&sys->own_events_pending, 1, memory_order_relaxed);
    return 0;
}

void own_events_drop_after(ssx_component *c, double t)
{
    ssx_own_event_list *list = &c->own_events;
    while (list->n > 0 && list->pending[list->n - 1].t > t) {
        list->n--;
    }
}

size_t own_events_pending_count(const ssx_component *c)
{
    return c->own_events.n;
}

void own_events_mark_at_step_end(ssx_component *c, size_t n)
{
    for (size_t k = n; k < c->own_events.n; ++k) {
        c->own_events.pending[k].at_step_end = 1;
    }
}

void own_events_keep_first(ssx_component *c, size_t n)
{
    if (c->own_events.n > n) {
        c->own_events.n = n;
    }
}

int own_events_earliest(const ssx_system *sys, double *t)
{
    if (!atomic_load_explicit(&sys->own_events_pending, memory_order_relaxed)) {
        return 0;
    }
    int found = 0;
    for (int i = 0; i < sys->n_components; ++i) {
        /* pending in time order: a component's first is its earliest */
        const ssx_own_event_list *list = &sys->components[i]->own_events;
        if (list->n > 0 && (!found || list->pending[0].t < *t)) {
            *t = list->pending[0].t;
            found = 1;
        }
    }
    return found;
}

/* The component whose first pending event (at or before t) is earliest, or -1. */
static int earliest(const ssx_system *sys, const size_t *next, double t)
{
    int best = -1;
    double best_t = INFINITY;
    for (int i = 0; i < sys->n_components; ++i) {
        const ssx_own_event_list *list = &sys->components[i]->own_events;
        if (next[i] < list->n && list->pending[next[i]].t <= t &&
            list->pending[next[i]].t < best_t) {
            best = i;
            best_t = list->pending[next[i]].t;
        }
    }
    return best;
}

int own_events_commit(ssx_system *sys, double t, own_event_committed committed, void *user)
{
    /* where no component reported, a system of thousands is not asked component by component
     * after every step (the workers that report have joined before the commit) */
    if (!atomic_load_explicit(&sys->own_events_pending, memory_order_relaxed)) {
        return 0;
    }
    int any = 0;
    for (int i = 0; i < sys->n_components && !any; ++i) {
        any = sys->components[i]->own_events.n > 0;
    }
    if (!any) {
        atomic_store_explicit(&sys->own_events_pending, 0, memory_order_relaxed);
        return 0;
    }
    size_t *next = calloc((size_t)sys->n_components, sizeof *next);
    if (next == NULL) {
        return fail(sys, -1, -1, t, "out of memory recording components' own events");
    }
    int status = 0;
    int i;
    while (status == 0 && (i = earliest(sys, next, t)) >= 0) {
        const ssx_own_event *e = &sys->components[i]->own_events.pending[next[i]++];
        ssx_event_record record = {
            .t = e->t,
            .micro = 0,
            .indicator = -1,
            .component = i,
            .own = e->kind,
            .clock = e->clock,
            .t_left = NAN,
            .t_right = NAN,
            .value_left = NAN,
            .value_right = NAN,
        };
        sys->stats.own_events++;
        status = committed(sys, &record, user);
    }
    /* what stays pending lies after t: move it to the front */
    int left = 0;
    for (int c = 0; c < sys->n_components; ++c) {
        ssx_own_event_list *list = &sys->components[c]->own_events;
        size_t kept = 0;
        for (size_t k = next[c]; k < list->n; ++k) {
            list->pending[kept++] = list->pending[k];
        }
        list->n = kept;
        left |= kept > 0;
    }
    atomic_store_explicit(&sys->own_events_pending, left, memory_order_relaxed);
    free(next);
    return status;
}

void own_events_clear(ssx_system *sys)
{
    for (int i = 0; i < sys->n_components; ++i) {
        sys->components[i]->own_events.n = 0;
    }
    atomic_store_explicit(&sys->own_events_pending, 0, memory_order_relaxed);
}

void own_event_list_free(ssx_own_event_list *list)
{
    free(list->pending);
    *list = (ssx_own_event_list){0};
}
