/* The observers a run reports to, and the dispatch from the time loop to them. */
#include "recording.h"

#include <stdlib.h>
#include <string.h>

#include "array.h"
#include "component.h"
#include "error.h"
#include "system.h"

/* ---------------------------------------------------------------- the history */

static int history_observer_start(ssx_observer *self, ssx_system *sys)
{
    ssx_history_observer *h = (ssx_history_observer *)self;
    int n = sys->n_components;
    int *columns = malloc(((size_t)n + 1) * sizeof *columns);
    double **views = realloc(h->output_views, ((size_t)n + 1) * sizeof *views);
    if (views != NULL) {
        h->output_views = views;
    }
    if (columns == NULL || views == NULL) {
        free(columns);
        return fail(sys, -1, -1, sys->time, "out of memory starting the history");
    }
    for (int i = 0; i < n; ++i) {
        columns[i] = sys->components[i]->n_outputs;
        views[i] = sys->components[i]->outputs;
    }
    int status = history_start(&h->history, n, columns);
    free(columns);
    if (status != 0) {
        return fail(sys, -1, -1, sys->time, "out of memory starting the history");
    }
    return 0;
}

static int history_observer_run_start(ssx_observer *self, ssx_system *sys, size_t n_steps)
{
    ssx_history_observer *h = (ssx_history_observer *)self;
    if (history_reserve(&h->history, n_steps) != 0) {
        return fail(sys, -1, -1, sys->time, "out of memory reserving history samples");
    }
    return 0;
}

static int history_observer_step_complete(ssx_observer *self, ssx_system *sys,
                                          const ssx_sample *sample)
{
    ssx_history_observer *h = (ssx_history_observer *)self;
    if (history_append(&h->history, sample->t, sample->micro,
                       (const double *const *)h->output_views) != 0) {
        return fail(sys, -1, -1, sample->t, "out of memory recording the sample at t=%.17g",
                    sample->t);
    }
    return 0;
}

static void history_observer_run_end(ssx_observer *self, ssx_system *sys)
{
    (void)sys;
    history_trim(&((ssx_history_observer *)self)->history);
}

static const ssx_observer_ops HISTORY_OPS = {
    .start = history_observer_start,
    .run_start = history_observer_run_start,
    .step_complete = history_observer_step_complete,
    .run_end = history_observer_run_end,
};

/* ---------------------------------------------------------------- decimation */

static int decimating(const ssx_recording *r)
{
    return r->output_interval > 1 || r->run_output_interval > 1;
}

static int decimator_keeps(ssx_decimator *d, const ssx_sample *sample)
{
    if (!sample->on_grid) {
        return 1;
    }
    int kept = (d->run_interval > 0 ? d->run_points % d->run_interval == 0
                                    : d->grid_points % d->interval == 0) ||
               sample->run_end;
    d->grid_points++;
    d->run_points++;
    return kept;
}

/* ---------------------------------------------------------------- the lists */

static int list_add(observer_list *list, ssx_observer *observer)
{
    if (array_reserve((void **)&list->items, &list->capacity, (size_t)list->n + 1,
                      sizeof *list->items, 4) != 0) {
        return -1;
    }
    list->items[list->n++] = observer;
    return 0;
}

static void release(ssx_observer *observer)
{
    if (observer->ops->release != NULL) {
        observer->ops->release(observer);
    }
}

static void list_free(observer_list *list)
{
    for (int k = 0; k < list->n; ++k) {
        release(list->items[k]);
    }
    free(list->items);
}

static int list_start(observer_list *list, ssx_system *sys)
{
    for (int k = 0; k < list->n; ++k) {
        ssx_observer *o = list->items[k];
        if (o->ops->start != NULL && o->ops->start(o, sys) != 0) {
            return -1;
        }
    }
    return 0;
}

static int list_run_start(observer_list *list, ssx_system *sys, size_t n_steps)
{
    for (int k = 0; k < list->n; ++k) {
        ssx_observer *o = list->items[k];
        if (o->ops->run_start != NULL && o->ops->run_start(o, sys, n_steps) != 0) {
            return -1;
        }
    }
    return 0;
}

static int list_step_complete(observer_list *list, ssx_system *sys, const ssx_sample *sample)
{
    for (int k = 0; k < list->n; ++k) {
        ssx_observer *o = list->items[k];
        if (o->ops->step_complete(o, sys, sample) != 0) {
            return -1;
        }
    }
    return 0;
}

static int list_state_restored(observer_list *list, ssx_system *sys, double t)
{
    for (int k = 0; k < list->n; ++k) {
        ssx_observer *o = list->items[k];
        if (o->ops->state_restored != NULL && o->ops->state_restored(o, sys, t) != 0) {
            return -1;
        }
    }
    return 0;
}

static int list_event(observer_list *list, ssx_system *sys, const ssx_event_record *record)
{
    for (int k = 0; k < list->n; ++k) {
        ssx_observer *o = list->items[k];
        if (o->ops->event != NULL && o->ops->event(o, sys, record) != 0) {
            return -1;
        }
    }
    return 0;
}

static void list_run_end(observer_list *list, ssx_system *sys)
{
    for (int k = 0; k < list->n; ++k) {
        ssx_observer *o = list->items[k];
        if (o->ops->run_end != NULL) {
            o->ops->run_end(o, sys);
        }
    }
}

/* ---------------------------------------------------------------- the recording */

ssx_recording *recording_new(int output_interval)
{
    ssx_recording *r = calloc(1, sizeof *r);
    if (r == NULL) {
        return NULL;
    }
    r->history.base.ops = &HISTORY_OPS;
    r->output_interval = output_interval;
    if (list_add(&r->kept, &r->history.base) != 0) {
        free(r);
        return NULL;
    }
    return r;
}

void recording_free(ssx_recording *r)
{
    if (r == NULL) {
        return;
    }
    list_free(&r->kept);
    list_free(&r->every);
    history_free(&r->history.history);
    free(r->history.output_views);
    free(r->events);
    free(r);
}

int recording_add_observer(ssx_recording *r, ssx_observer *observer)
{
    if (list_add(&r->kept, observer) != 0) {
        release(observer);
        return -1;
    }
    observer->id = ++r->next_id;
    return observer->id;
}

int recording_remove_observer(ssx_recording *r, int id)
{
    for (int k = 0; k < r->kept.n; ++k) {
        ssx_observer *o = r->kept.items[k];
        if (o != &r->history.base && o->id == id) {
            memmove(&r->kept.items[k], &r->kept.items[k + 1],
                    (size_t)(r->kept.n - k - 1) * sizeof *r->kept.items);
            r->kept.n--;
            release(o);
            return 0;
        }
    }
    return -1;
}

int recording_add_sample_observer(ssx_recording *r, ssx_observer *observer)
{
    if (list_add(&r->every, observer) != 0) {
        release(observer);
        return -1;
    }
    return 0;
}

void recording_keep_history(ssx_recording *r, int keep)
{
    r->history_off = !keep;
}

/* At the start: the history first among the kept observers, or gone with its samples. */
static int place_history(ssx_recording *r)
{
    int keep = !r->history_off;
    int kept = r->kept.n > 0 && r->kept.items[0] == &r->history.base;
    if (keep && !kept) {
        if (list_add(&r->kept, &r->history.base) != 0) {
            return -1;
        }
        /* first again, as it was */
        memmove(&r->kept.items[1], &r->kept.items[0],
                (size_t)(r->kept.n - 1) * sizeof *r->kept.items);
        r->kept.items[0] = &r->history.base;
    } else if (!keep && kept) {
        memmove(&r->kept.items[0], &r->kept.items[1],
                (size_t)(r->kept.n - 1) * sizeof *r->kept.items);
        r->kept.n--;
        history_free(&r->history.history);
    }
    return 0;
}

int recording_start(ssx_system *sys)
{
    ssx_recording *r = sys->recording;
    if (place_history(r) != 0) {
        return fail(sys, -1, -1, sys->time, "out of memory starting the history");
    }
    r->n_events = 0;
    r->decimator = (ssx_decimator){.interval = r->output_interval};
    r->run_end_time = sys->time;
    return list_start(&r->kept, sys) != 0 || list_start(&r->every, sys) != 0 ? -1 : 0;
}

int recording_run_start(ssx_system *sys, size_t n_steps, double tf)
{
    ssx_recording *r = sys->recording;
    if (r->history_off) {
        (void)place_history(r); /* removing it takes no memory */
    }
    r->run_end_time = tf;
    size_t kept_steps = n_steps;
    if (decimating(r)) {
        /* The run's start point was recorded before it: the run's first step ends at its 1st
         * point. Room for the points kept, plus the end point: events grow the history as
         * they come. */
        ssx_decimator *d = &r->decimator;
        d->run_interval = r->run_output_interval;
        d->run_points = 1;
        int every = d->run_interval > 0 ? d->run_interval : d->interval;
        kept_steps = n_steps / (size_t)every + 1;
    }
    return list_run_start(&r->kept, sys, kept_steps) != 0 ||
                   list_run_start(&r->every, sys, n_steps) != 0
               ? -1
               : 0;
}

void recording_run_end(ssx_system *sys)
{
    list_run_end(&sys->recording->kept, sys);
    list_run_end(&sys->recording->every, sys);
}

static int step_complete(ssx_system *sys, const ssx_sample *sample)
{
    ssx_recording *r = sys->recording;
    int kept = !decimating(r) || decimator_keeps(&r->decimator, sample);
    if (kept && list_step_complete(&r->kept, sys, sample) != 0) {
        return -1;
    }
    return list_step_complete(&r->every, sys, sample);
}

int record_grid_point(ssx_system *sys, double t)
{
    ssx_sample sample = {.t = t,
                         .micro = 0,
                         .on_grid = 1,
                         .run_end = t == sys->recording->run_end_time};
    return step_complete(sys, &sample);
}

int record_sample(ssx_system *sys, double t, int micro)
{
    ssx_sample sample = {.t = t, .micro = micro, .on_grid = 0, .run_end = 0};
    return step_complete(sys, &sample);
}

int record_state_restored(ssx_system *sys, double t)
{
    ssx_recording *r = sys->recording;
    return list_state_restored(&r->kept, sys, t) != 0 ||
                   list_state_restored(&r->every, sys, t) != 0
               ? -1
               : 0;
}

int record_event(ssx_system *sys, const ssx_event_record *record)
{
    ssx_recording *r = sys->recording;
    if (array_reserve((void **)&r->events, &r->events_capacity, r->n_events + 1,
                      sizeof *r->events, 16) != 0) {
        return fail(sys, record->component, record->indicator, record->t,
                    "out of memory recording an event");
    }
    r->events[r->n_events++] = *record;
    return list_event(&r->kept, sys, record) != 0 || list_event(&r->every, sys, record) != 0
               ? -1
               : 0;
}
