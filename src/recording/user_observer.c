/* The observers a user adds (ssx_add_observer): callbacks with their user pointer, behind the
 * engine's observer interface. */
#include <stdlib.h>

#include "error.h"
#include "recording.h"
#include "system.h"

typedef struct {
    ssx_observer base;
    ssx_observer_callbacks callbacks;
    void *user;
    int started; /* added after ssx_initialize: started by the next run */
} user_observer;

static int failed(ssx_system *sys, const user_observer *o, double t, const char *callback)
{
    return fail_kind(sys, SSX_ERROR_CALLBACK, -1, -1, t, "observer %d: its %s callback failed at "
                     "t=%.17g", o->base.id, callback, t);
}

static int user_start(ssx_observer *self, ssx_system *sys)
{
    user_observer *o = (user_observer *)self;
    o->started = 1;
    return o->callbacks.start == NULL || o->callbacks.start(o->user, sys->time) == 0
               ? 0
               : failed(sys, o, sys->time, "start");
}

static int user_run_start(ssx_observer *self, ssx_system *sys, size_t n_steps)
{
    (void)n_steps;
    return ((user_observer *)self)->started ? 0 : user_start(self, sys);
}

static int user_step_complete(ssx_observer *self, ssx_system *sys, const ssx_sample *sample)
{
    user_observer *o = (user_observer *)self;
    return o->callbacks.step_complete == NULL ||
                   o->callbacks.step_complete(o->user, sample->t, sample->micro) == 0
               ? 0
               : failed(sys, o, sample->t, "step_complete");
}

static int user_state_restored(ssx_observer *self, ssx_system *sys, double t)
{
    user_observer *o = (user_observer *)self;
    return o->callbacks.state_restored == NULL || o->callbacks.state_restored(o->user, t) == 0
               ? 0
               : failed(sys, o, t, "state_restored");
}

static int user_event(ssx_observer *self, ssx_system *sys, const ssx_event_record *record)
{
    user_observer *o = (user_observer *)self;
    return o->callbacks.event == NULL || o->callbacks.event(o->user, record) == 0
               ? 0
               : failed(sys, o, record->t, "event");
}

static void user_run_end(ssx_observer *self, ssx_system *sys)
{
    (void)sys;
    user_observer *o = (user_observer *)self;
    if (o->callbacks.run_end != NULL) {
        (void)o->callbacks.run_end(o->user); /* the run's status stands, whatever this says */
    }
}

static void user_release(ssx_observer *self)
{
    free(self);
}

static const ssx_observer_ops USER_OPS = {
    .start = user_start,
    .run_start = user_run_start,
    .step_complete = user_step_complete,
    .state_restored = user_state_restored,
    .event = user_event,
    .run_end = user_run_end,
    .release = user_release,
};

int ssx_add_observer(ssx_system *sys, const ssx_observer_callbacks *callbacks, void *user)
{
    if (callbacks == NULL) {
        return fail_config(sys, -1, -1, sys->time, "ssx_add_observer: no callbacks given");
    }
    user_observer *o = calloc(1, sizeof *o);
    if (o == NULL) {
        return fail_config(sys, -1, -1, sys->time, "out of memory adding an observer");
    }
    *o = (user_observer){.base = {.ops = &USER_OPS}, .callbacks = *callbacks, .user = user};
    int id = recording_add_observer(sys->recording, &o->base);
    if (id < 0) {
        return fail_config(sys, -1, -1, sys->time, "out of memory adding an observer");
    }
    return id;
}

int ssx_remove_observer(ssx_system *sys, int observer)
{
    if (recording_remove_observer(sys->recording, observer) != 0) {
        return fail_config(sys, -1, -1, sys->time, "ssx_remove_observer: no observer %d",
                           observer);
    }
    return 0;
}

int ssx_set_history(ssx_system *sys, int keep)
{
    recording_keep_history(sys->recording, keep != 0);
    return 0;
}
