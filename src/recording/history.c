/* Reference-counted history buffers that grow as they are used. */
#include "history.h"

#include <stdlib.h>
#include <string.h>

#include "large_buffer.h"

/* Rows of a new history, and the least growth beyond a reservation. */
enum { INITIAL_ROWS = 256 };

static void buffer_free(ssx_buffer *buffer)
{
    large_buffer_free(buffer->data, buffer->bytes);
    buffer->data = NULL;
    buffer->bytes = 0;
}

/* Keeps the contents up to the smaller size. Returns 0, or -1 with the buffer unchanged. */
static int buffer_resize(ssx_buffer *buffer, size_t bytes)
{
    void *data = buffer->data == NULL ? large_buffer_allocate(bytes)
                                      : large_buffer_resize(buffer->data, buffer->bytes, bytes);
    if (data == NULL) {
        return -1;
    }
    buffer->data = data;
    buffer->bytes = bytes;
    return 0;
}

static size_t row_bytes(const ssx_history_block *b, int component)
{
    return (size_t)b->columns[component] * sizeof(double);
}

static void block_free(ssx_history_block *b)
{
    buffer_free(&b->outputs);
    free(b->values);
    free(b->columns);
    buffer_free(&b->time);
    buffer_free(&b->micro);
    free(b);
}

static size_t total_columns(const ssx_history_block *b)
{
    size_t total = 0;
    for (int c = 0; c < b->n_components; ++c) {
        total += (size_t)b->columns[c];
    }
    return total;
}

/* Gives the block room for `capacity` rows, keeping its first `rows` (no more than either
 * capacity). The outputs move into a new mapping laid out for the new capacity. On failure
 * some buffers have the new size and the others the old one: the capacity becomes the smaller
 * of the two, which every buffer holds (each buffer knows its own size for freeing). */
static int block_resize(ssx_history_block *b, size_t capacity, size_t rows)
{
    ssx_buffer outputs = {.bytes = (capacity * total_columns(b) + 1) * sizeof(double)};
    outputs.data = large_buffer_allocate(outputs.bytes);
    if (outputs.data == NULL) {
        return -1;
    }
    if (buffer_resize(&b->time, capacity * sizeof(double)) != 0 ||
        buffer_resize(&b->micro, capacity * sizeof(int)) != 0) {
        buffer_free(&outputs);
        b->capacity = capacity < b->capacity ? capacity : b->capacity;
        return -1;
    }
    double *at = outputs.data;
    for (int c = 0; c < b->n_components; ++c) {
        if (rows > 0 && b->columns[c] > 0) {
            memcpy(at, b->values[c], rows * row_bytes(b, c));
        }
        b->values[c] = at;
        at += capacity * (size_t)b->columns[c];
    }
    buffer_free(&b->outputs);
    b->outputs = outputs;
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
    if (block_resize(b, capacity, 0) != 0) {
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
    h->last_growth = 0;
    h->copied_for_reader = 0;
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
    memcpy(b->time.data, old->time.data, h->length * sizeof(double));
    memcpy(b->micro.data, old->micro.data, h->length * sizeof(int));
    for (int c = 0; c < b->n_components; ++c) {
        if (b->columns[c] > 0) {
            memcpy(b->values[c], old->values[c], h->length * row_bytes(b, c));
        }
    }
    h->block = b;
    h->copied_for_reader = 1;
    history_block_release(old);
    return 0;
}

/* Room for `needed` rows. A block no reader holds is resized in place. A held one is copied
 * into a new block of at least twice the rows in use: in a loop of short runs whose last
 * result is still held, the history is then copied O(log n) times, not once per run. */
static int make_room(ssx_history *h, size_t needed)
{
    if (needed <= h->block->capacity) {
        return 0;
    }
    if (!is_shared(h->block)) {
        return block_resize(h->block, needed, h->length);
    }
    size_t doubled = 2 * h->length;
    return move_to_new_block(h, needed > doubled ? needed : doubled);
}

/* Rows reserved ahead for a known grid are limited to this much memory. */
static const size_t RESERVE_MAX_BYTES = 64 * 1024 * 1024;

static size_t sample_bytes(const ssx_history_block *b)
{
    size_t bytes = sizeof(double) + sizeof(int);
    for (int c = 0; c < b->n_components; ++c) {
        bytes += row_bytes(b, c);
    }
    return bytes;
}

int history_reserve(ssx_history *h, size_t extra)
{
    size_t limit = RESERVE_MAX_BYTES / sample_bytes(h->block);
    return make_room(h, h->length + (extra < limit ? extra : limit));
}

int history_append(ssx_history *h, double t, int micro, const double *const *outputs)
{
    if (h->length == h->block->capacity) {
        /* beyond the reserved grid: event samples, or a grid larger than the reservation */
        size_t growth = h->last_growth + h->last_growth / 2;
        growth = growth < INITIAL_ROWS ? INITIAL_ROWS : growth;
        if (make_room(h, h->block->capacity + growth) != 0) {
            return -1;
        }
        h->last_growth = growth;
    }
    ssx_history_block *b = h->block;
    size_t row = h->length;
    ((double *)b->time.data)[row] = t;
    ((int *)b->micro.data)[row] = micro;
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
    if (h->block != NULL && !is_shared(h->block) && !h->copied_for_reader &&
        h->block->capacity > h->length && h->length > 0) {
        /* a failed shrink only keeps some buffers larger than needed */
        (void)block_resize(h->block, h->length, h->length);
    }
    h->copied_for_reader = 0;
}

size_t history_bytes(const ssx_history *h)
{
    return h->block != NULL ? h->block->capacity * sample_bytes(h->block) : 0;
}
