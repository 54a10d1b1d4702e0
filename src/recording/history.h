/* The recorded history: one time axis with its micro index, and per component a row-major
 * matrix of output values, the matrices one after the other in one buffer.
 *
 * The buffers live in a reference-counted block, so that readers (numpy arrays in Python) can
 * keep the samples they were given without a copy. The history holds one reference; each
 * ssx_history_retain adds one. Samples are only ever appended, so a reader's rows are never
 * written again; growth moves the buffers (realloc, mremap, the matrices copied into their new
 * places) only while no reader holds the block, and otherwise copies the samples into a new
 * block and leaves the old one to its readers. */
#ifndef SSX_HISTORY_H
#define SSX_HISTORY_H

#include <stdatomic.h>
#include <stddef.h>

/* One growable buffer; `bytes` is its allocated size (it decides how it was allocated). */
typedef struct {
    void *data;
    size_t bytes;
} ssx_buffer;

typedef struct ssx_history_block {
    atomic_long references; /* released from any thread (a collected numpy array) */
    size_t capacity;        /* rows every buffer holds */
    int n_components;
    int *columns;           /* outputs per component */
    ssx_buffer time;        /* double per row */
    ssx_buffer micro;       /* int per row */
    /* every component's rows, component after component: one mapping (in large pages where
     * it is large), so a step's row reaches one page per 2 MiB of columns, not one per
     * component */
    ssx_buffer outputs;
    double **values;        /* per component: its capacity x columns doubles in outputs */
} ssx_history_block;

typedef struct {
    size_t length;
    size_t last_growth; /* rows added by the last growth beyond a reservation */
    int copied_for_reader; /* since the last trim, samples were copied away from a reader */
    ssx_history_block *block;
} ssx_history;

void history_free(ssx_history *h);
/* Drops every sample (readers keep theirs) and fixes the matrix shapes from the output counts. */
int history_start(ssx_history *h, int n_components, const int *columns);
/* Makes room for `extra` more samples, but for no more than 64 MiB of them: a grid known in
 * advance is recorded without moving, and a huge one (a typo in dt) grows as it is used. */
int history_reserve(ssx_history *h, size_t extra);
/* Appends one sample. Beyond the reserved room (events, a grid larger than the reservation)
 * each growth adds 1.5 times the previous one: amortized O(1) per sample, with slack in
 * proportion to the unplanned samples, not to the whole history. */
int history_append(ssx_history *h, double t, int micro, const double *const *outputs);
/* At the end of a run: gives back the room beyond the recorded samples, unless a reader holds
 * the block or the run had to copy the samples away from a reader. That copy's room of twice
 * the samples stays, so that the next run, while this run's result holds the block, fills it
 * instead of copying again. */
void history_trim(ssx_history *h);
size_t history_bytes(const ssx_history *h);

ssx_history_block *history_block_retain(ssx_history_block *block);
void history_block_release(ssx_history_block *block);

#endif
