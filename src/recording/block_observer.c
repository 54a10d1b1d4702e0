/* Block observers (ssx_add_block_observer): the kept samples gathered into blocks of rows, each
 * handed to the user's writer when it is full and at the end of a run, so that a writer in
 * Python pays its call once per block, not per sample, and memory stays one block. */
#include <stdlib.h>
#include <string.h>

#include "component.h"
#include "error.h"
#include "recording.h"
#include "system.h"

typedef struct {
    ssx_observer base;
    ssx_block_writer write;
    void *user;
    size_t rows; /* a block's */
    size_t n;    /* rows filled */
    size_t columns;
    double *t;
    int *micro;
    double *values; /* rows x columns, row-major */
} block_observer;

static void free_block(block_observer *o)
{
    free(o->t);
    free(o->micro);
    free(o->values);
    o->t = o->values = NULL;
    o->micro = NULL;
}

/* The writer answers 0 (written), > 0 (written, but stop the run) or < 0 (not written: the rows
 * stay, handed again when the run ends, so that a writer stopped before it began, by Ctrl-C in
 * Python, loses none of them). */
static int hand_over(ssx_system *sys, block_observer *o, double t)
{
    if (o->n == 0) {
        return 0;
    }
    int status = o->write(o->user, o->t, o->micro, o->values, o->n, o->columns);
    if (status >= 0) {
        o->n = 0;
    }
    if (status != 0) {
        return fail_kind(sys, SSX_ERROR_CALLBACK, -1, -1, t,
                         "observer %d: its block writer failed at t=%.17g", o->base.id, t);
    }
    return 0;
}

static int block_start(ssx_observer *self, ssx_system *sys)
{
    block_observer *o = (block_observer *)self;
    size_t columns = 0;
    for (int i = 0; i < sys->n_components; ++i) {
        columns += (size_t)sys->components[i]->n_outputs;
    }
    free_block(o);
    o->n = 0;
    o->columns = columns;
    o->t = malloc(o->rows * sizeof *o->t);
    o->micro = malloc(o->rows * sizeof *o->micro);
    o->values = malloc((o->rows * columns + 1) * sizeof *o->values);
    if (o->t == NULL || o->micro == NULL || o->values == NULL) {
        free_block(o);
        return fail(sys, -1, -1, sys->time, "out of memory for a block of %zu samples", o->rows);
    }
    return 0;
}

static int block_run_start(ssx_observer *self, ssx_system *sys, size_t n_steps)
{
    (void)n_steps;
    /* added after ssx_initialize: its block is made by the first run */
    return ((block_observer *)self)->t != NULL ? 0 : block_start(self, sys);
}

static int block_step_complete(ssx_observer *self, ssx_system *sys, const ssx_sample *sample)
{
    block_observer *o = (block_observer *)self;
    double *row = o->values + o->n * o->columns;
    for (int i = 0; i < sys->n_components; ++i) {
        const ssx_component *c = sys->components[i];
        memcpy(row, c->outputs, (size_t)c->n_outputs * sizeof *row);
        row += c->n_outputs;
    }
    o->t[o->n] = sample->t;
    o->micro[o->n] = sample->micro;
    o->n++;
    /* the run's last point is handed over with the run's status still to come */
    return o->n == o->rows || sample->run_end ? hand_over(sys, o, sample->t) : 0;
}

/* After a run that ended early (a failure, a component's request to stop, a block its writer
 * did not write): what was gathered before is written too. The run's own status stands,
 * whatever the writer says. */
static void block_run_end(ssx_observer *self, ssx_system *sys)
{
    (void)sys;
    block_observer *o = (block_observer *)self;
    size_t n = o->n;
    o->n = 0;
    if (n > 0) {
        (void)o->write(o->user, o->t, o->micro, o->values, n, o->columns);
    }
}

static void block_release(ssx_observer *self)
{
    free_block((block_observer *)self);
    free(self);
}

static const ssx_observer_ops BLOCK_OPS = {
    .start = block_start,
    .run_start = block_run_start,
    .step_complete = block_step_complete,
    .run_end = block_run_end,
    .release = block_release,
};

int ssx_add_block_observer(ssx_system *sys, size_t rows, ssx_block_writer write, void *user)
{
    if (write == NULL || rows == 0) {
        return fail_config(sys, -1, -1, sys->time,
                           "ssx_add_block_observer: a writer and at least one row are needed");
    }
    block_observer *o = calloc(1, sizeof *o);
    if (o == NULL) {
        return fail_config(sys, -1, -1, sys->time, "out of memory adding an observer");
    }
    *o = (block_observer){.base = {.ops = &BLOCK_OPS}, .write = write, .user = user, .rows = rows};
    int id = recording_add_observer(sys->recording, &o->base);
    return id >= 0 ? id : fail_config(sys, -1, -1, sys->time, "out of memory adding an observer");
}
