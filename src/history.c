/* Reference-counted history buffers that grow as they are used. */
#include "history.h"

#include <stdlib.h>
#include <string.h>

/* Rows of a new history. Growth then doubles the capacity: amortized O(1) per sample, and
 * with glibc a large buffer grows by mremap, so only the rows written become resident. */
enum { INITIAL_ROWS = 256 };

static void block_free(ssx_history_block *b)
{
    for (int c = 0; c < b->n_components; ++c) {
        free(b->values[c]);
    }
    free(b->values);
    free(b->columns);
    free(b->time);
    free(b->micro);
    free(b);
}

static int resize_buffers(ssx_history_block *b, size_t capacity)
{
    double *time = realloc(b->time, capacity * sizeof *time);
    if (time == NULL) {
        return -1;
    }
    b->time = time;
    int *micro = realloc(b->micro, capacity * sizeof *micro);
    if (micro == NULL) {
        return -1;
    }
    b->micro = micro;
    for (int c = 0; c < b->n_components; ++c) {
        if (b->columns[c] == 0) {
            continue;
        }
        double *values = realloc(b->values[c], capacity * (size_t)b->columns[c] * sizeof *values);
        if (values == NULL) {
            return -1;
        }
        b->values[c] = values;
    }
    return 0;
}

/* Resizes every buffer of the block to `capacity` rows. On failure some buffers have the new
 * size and the others the old one: the capacity becomes the smaller of the two, which every
 * buffer holds. */
static int block_resize(ssx_history_block *b, size_t capacity)
{
    if (resize_buffers(b, capacity) != 0) {
        b->capacity = capacity < b->capacity ? capacity : b->capacity;
        return -1;
    }
    b->capacity = capacity;
    return 0;
}

static ssx_history_block *block_new(int n_components, const int *columns, size_t capacity)
{
    ssx_history_block *b = calloc(1, sizeof *b);
    if (b == NULL) {
        return NULL;
    }
    atomic_init(&b->references, 1);
    b->values = calloc((size_t)n_components + 1, sizeof *b->values);
    b->columns = calloc((size_t)n_components + 1, sizeof *b->columns);
    if (b->values == NULL || b->columns == NULL) {
        block_free(b);
        return NULL;
    }
    b->n_components = n_components;
    memcpy(b->columns, columns, (size_t)n_components * sizeof *columns);
    if (block_resize(b, capacity) != 0) {
        block_free(b);
        return NULL;
    }
    return b;
}

ssx_history_block *history_block_retain(ssx_history_block *block)
{
    atomic_fetch_add(&block->references, 1);
    return block;
}

void history_block_release(ssx_history_block *block)
{
    if (block != NULL && atomic_fetch_sub(&block->references, 1) == 1) {
        block_free(block);
    }
}

void history_free(ssx_history *h)
{
    history_block_release(h->block);
    h->block = NULL;
    h->length = 0;
}

int history_start(ssx_history *h, int n_components, const int *columns)
{
    history_free(h);
    h->block = block_new(n_components, columns, INITIAL_ROWS);
    return h->block != NULL ? 0 : -1;
}

/* Only this history can hold the last reference, and only this thread adds references, so a
 * count of 1 stays 1 while the block is resized. */
static int is_shared(ssx_history_block *b)
{
    return atomic_load(&b->references) > 1;
}

/* A reader holds the block: its rows must not move, so the samples go to a new block. */
static int move_to_new_block(ssx_history *h, size_t capacity)
{
    ssx_history_block *old = h->block;
    ssx_history_block *b = block_new(old->n_components, old->columns, capacity);
    if (b == NULL) {
        return -1;
    }
    memcpy(b->time, old->time, h->length * sizeof *b->time);
    memcpy(b->micro, old->micro, h->length * sizeof *b->micro);
    for (int c = 0; c < b->n_components; ++c) {
        if (b->columns[c] > 0) {
            memcpy(b->values[c], old->values[c],
                   h->length * (size_t)b->columns[c] * sizeof *b->values[c]);
        }
    }
    h->block = b;
    history_block_release(old);
    return 0;
}

static int grow(ssx_history *h)
{
    size_t capacity = h->block->capacity > 0 ? 2 * h->block->capacity : INITIAL_ROWS;
    return is_shared(h->block) ? move_to_new_block(h, capacity)
                               : block_resize(h->block, capacity);
}

int history_append(ssx_history *h, double t, int micro, const double *const *outputs)
{
    if (h->length == h->block->capacity && grow(h) != 0) {
        return -1;
    }
    ssx_history_block *b = h->block;
    size_t row = h->length;
    b->time[row] = t;
    b->micro[row] = micro;
    /* a plain loop: rows are a few doubles, too short to pay for a memcpy call */
    for (int c = 0; c < b->n_components; ++c) {
        size_t n = (size_t)b->columns[c];
        double *dst = b->values[c] + row * n;
        const double *src = outputs[c];
        for (size_t j = 0; j < n; ++j) {
            dst[j] = src[j];
        }
    }
    h->length++;
    return 0;
}

void history_trim(ssx_history *h)
{
    if (h->block != NULL && !is_shared(h->block) && h->block->capacity > h->length &&
        h->length > 0) {
        /* a failed shrink only keeps some buffers larger than needed */
        (void)block_resize(h->block, h->length);
    }
}

size_t history_bytes(const ssx_history *h)
{
    if (h->block == NULL) {
        return 0;
    }
    size_t per_sample = sizeof(double) + sizeof(int);
    for (int c = 0; c < h->block->n_components; ++c) {
        per_sample += (size_t)h->block->columns[c] * sizeof(double);
    }
    return h->block->capacity * per_sample;
}
