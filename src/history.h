/* The recorded history: one time axis with its micro index, and per component a row-major
 * matrix of output values.
 *
 * The buffers live in a reference-counted block, so that readers (numpy arrays in Python) can
 * keep the samples they were given without a copy. The history holds one reference; each
 * ssx_history_retain adds one. Samples are only ever appended, so a reader's rows are never
 * written again; growth moves the buffers in place (realloc) only while no reader holds the
 * block, and otherwise copies the samples into a new block and leaves the old one to its
 * readers. */
#ifndef SSX_HISTORY_H
#define SSX_HISTORY_H

#include <stdatomic.h>
#include <stddef.h>

typedef struct ssx_history_block {
    atomic_long references; /* released from any thread (a collected numpy array) */
    size_t capacity;
    int n_components;
    int *columns;     /* outputs per component */
    double *time;
    int *micro;
    double **values;  /* per component: capacity x columns */
} ssx_history_block;

typedef struct {
    size_t length;
    ssx_history_block *block;
} ssx_history;

void history_free(ssx_history *h);
/* Drops every sample (readers keep theirs) and fixes the matrix shapes from the output counts. */
int history_start(ssx_history *h, int n_components, const int *columns);
/* Appends one sample; the room grows geometrically (twice the capacity), as it is used. */
int history_append(ssx_history *h, double t, int micro, const double *const *outputs);
/* Gives back the room beyond the recorded samples, unless a reader holds the block. */
void history_trim(ssx_history *h);
size_t history_bytes(const ssx_history *h);

ssx_history_block *history_block_retain(ssx_history_block *block);
void history_block_release(ssx_history_block *block);

#endif
