/* The record hooks observer (see record_hooks.h). */
#include "record_hooks.h"

#include <stdlib.h>

#include "component_calls.h"
#include "system.h"

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

static void record_hooks_release(ssx_observer *self)
{
    free(self);
}

static const ssx_observer_ops RECORD_HOOKS_OPS = {
    .step_complete = record_hooks_step_complete,
    .release = record_hooks_release,
};

ssx_observer *record_hooks_observer_new(void)
{
    ssx_observer *observer = calloc(1, sizeof *observer);
    if (observer != NULL) {
        observer->ops = &RECORD_HOOKS_OPS;
    }
    return observer;
}
