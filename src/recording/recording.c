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

static int decimator_start(ssx_observer *self, ssx_system *sys)
{
    ssx_decimator *d = (ssx_decimator *)self;
    d->grid_points = 0;
    return d->next->ops->start(d->next, sys);
}

/* The run's start point was recorded before it: the run's first step ends at its 1st point.
 * Room for the points kept, plus the end point: events grow the history as they come. */
static int decimator_run_start(ssx_observer *self, ssx_system *sys, size_t n_steps)
{
    ssx_decimator *d = (ssx_decimator *)self;
    d->run_interval = sys->recording.run_output_interval;
    d->run_points = 1;
    int every = d->run_interval > 0 ? d->run_interval : d->interval;
    return d->next->ops->run_start(d->next, sys, n_steps / (size_t)every + 1);
}

static int decimator_step_complete(ssx_observer *self, ssx_system *sys, const ssx_sample *sample)
{
    ssx_decimator *d = (ssx_decimator *)self;
    if (sample->on_grid) {
        int kept = (d->run_interval > 0 ? d->run_points % d->run_interval == 0
                                        : d->grid_points % d->interval == 0) ||
                   sample->run_end;
        d->grid_points++;
        d->run_points++;
        if (!kept) {
            return 0;
        }
    }
    return d->next->ops->step_complete(d->next, sys, sample);
}

static void decimator_run_end(ssx_observer *self, ssx_system *sys)
{
    ssx_decimator *d = (ssx_decimator *)self;
    d->next->ops->run_end(d->next, sys);
}

/* In front of the history only, whose ops it calls without checking them for NULL. */
static const ssx_observer_ops DECIMATOR_OPS = {
    .start = decimator_start,
    .run_start = decimator_run_start,
    .step_complete = decimator_step_complete,
    .run_end = decimator_run_end,
};

/* ---------------------------------------------------------------- record hooks */

static int record_hooks_step_complete(ssx_observer *self, ssx_system *sys,
                                      const ssx_sample *sample)
{
    (void)self;
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        if (c->hooks.record != NULL && component_record(sys, c, sample->t) != 0) {
            return -1;
        }
    }
    return 0;
}

static const ssx_observer_ops RECORD_HOOKS_OPS = {.step_complete = record_hooks_step_complete};

/* ---------------------------------------------------------------- the recording */

void recording_init(ssx_recording *r, int output_interval)
{
    memset(r, 0, sizeof *r);
    r->history.base.ops = &HISTORY_OPS;
    r->decimator.base.ops = &DECIMATOR_OPS;
    r->decimator.next = &r->history.base;
    r->record_hooks.ops = &RECORD_HOOKS_OPS;
    r->output_interval = output_interval;
}

/* The history itself when every point is kept: no decimator call per sample. */
static ssx_observer *history_or_decimator(ssx_recording *r)
{
    return r->output_interval > 1 || r->run_output_interval > 1 ? &r->decimator.base
                                                                 : &r->history.base;
}

void recording_free(ssx_recording *r)
{
    history_free(&r->history.history);
    free(r->history.output_views);
    free(r->events);
}

static int has_record_hooks(const ssx_system *sys)
{
    for (int i = 0; i < sys->n_components; ++i) {
        if (sys->components[i]->hooks.record != NULL) {
            return 1;
        }
    }
    return 0;
}

int recording_start(ssx_system *sys)
{
    ssx_recording *r = &sys->recording;
    r->n_events = 0;
    r->n_observers = 0;
    r->decimator.interval = r->output_interval;
    r->decimator.run_interval = 0;
    r->observers[r->n_observers++] = history_or_decimator(r);
    /* most systems have no record hook: no call for them on every sample */
    if (has_record_hooks(sys)) {
        r->observers[r->n_observers++] = &r->record_hooks;
    }
    r->run_end_time = sys->time;
    for (int k = 0; k < r->n_observers; ++k) {
        ssx_observer *o = r->observers[k];
        if (o->ops->start != NULL && o->ops->start(o, sys) != 0) {
            return -1;
        }
    }
    return 0;
}

int recording_run_start(ssx_system *sys, size_t n_steps, double tf)
{
    ssx_recording *r = &sys->recording;
    r->run_end_time = tf;
    /* the run's own interval may call for the decimator (its start only began the history,
     * which is started already) */
    r->observers[0] = history_or_decimator(r);
    for (int k = 0; k < r->n_observers; ++k) {
        ssx_observer *o = r->observers[k];
        if (o->ops->run_start != NULL && o->ops->run_start(o, sys, n_steps) != 0) {
            return -1;
        }
    }
    return 0;
}

void recording_run_end(ssx_system *sys)
{
    ssx_recording *r = &sys->recording;
    for (int k = 0; k < r->n_observers; ++k) {
        ssx_observer *o = r->observers[k];
        if (o->ops->run_end != NULL) {
            o->ops->run_end(o, sys);
        }
    }
}

static int step_complete(ssx_system *sys, const ssx_sample *sample)
{
    ssx_recording *r = &sys->recording;
    for (int k = 0; k < r->n_observers; ++k) {
        ssx_observer *o = r->observers[k];
        if (o->ops->step_complete(o, sys, sample) != 0) {
            return -1;
        }
    }
    return 0;
}

int record_grid_point(ssx_system *sys, double t)
{
    ssx_sample sample = {.t = t,
                         .micro = 0,
                         .on_grid = 1,
                         .run_end = t == sys->recording.run_end_time};
    return step_complete(sys, &sample);
}

int record_sample(ssx_system *sys, double t, int micro)
{
    ssx_sample sample = {.t = t, .micro = micro, .on_grid = 0, .run_end = 0};
    return step_complete(sys, &sample);
}

int record_state_restored(ssx_system *sys, double t)
{
    ssx_recording *r = &sys->recording;
    for (int k = 0; k < r->n_observers; ++k) {
        ssx_observer *o = r->observers[k];
        if (o->ops->state_restored != NULL && o->ops->state_restored(o, sys, t) != 0) {
            return -1;
        }
    }
    return 0;
}

int record_event(ssx_system *sys, const ssx_event_record *record)
{
    ssx_recording *r = &sys->recording;
    if (array_reserve((void **)&r->events, &r->events_capacity, r->n_events + 1,
                      sizeof *r->events, 16) != 0) {
        return fail(sys, record->component, record->indicator, record->t,
                    "out of memory recording an event");
    }
    r->events[r->n_events++] = *record;
    for (int k = 0; k < r->n_observers; ++k) {
        ssx_observer *o = r->observers[k];
        if (o->ops->event != NULL && o->ops->event(o, sys, record) != 0) {
            return -1;
        }
    }
    return 0;
}
