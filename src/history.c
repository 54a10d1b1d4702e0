/* Growable history buffers. */
#include "history.h"

#include <stdlib.h>
#include <string.h>

void history_free(ssx_history *h)
{
    for (int c = 0; c < h->n_components; ++c) {
        free(h->values[c]);
    }
    free(h->values);
    free(h->columns);
    free(h->time);
    free(h->micro);
    memset(h, 0, sizeof *h);
}

int history_start(ssx_history *h, int n_components, const int *columns)
{
    history_free(h);
    h->values = calloc((size_t)n_components + 1, sizeof *h->values);
    h->columns = calloc((size_t)n_components + 1, sizeof *h->columns);
    if (h->values == NULL || h->columns == NULL) {
        history_free(h);
        return -1;
    }
    h->n_components = n_components;
    memcpy(h->columns, columns, (size_t)n_components * sizeof *columns);
    return 0;
}

static int set_capacity(ssx_history *h, size_t capacity)
{
    double *time = realloc(h->time, capacity * sizeof *time);
    if (time == NULL) {
        return -1;
    }
    h->time = time;
    int *micro = realloc(h->micro, capacity * sizeof *micro);
    if (micro == NULL) {
        return -1;
    }
    h->micro = micro;
    for (int c = 0; c < h->n_components; ++c) {
        if (h->columns[c] == 0) {
            continue;
        }
        double *values = realloc(h->values[c], capacity * (size_t)h->columns[c] * sizeof *values);
        if (values == NULL) {
            return -1;
        }
        h->values[c] = values;
    }
    h->capacity = capacity;
    return 0;
}

int history_reserve(ssx_history *h, size_t extra)
{
    size_t needed = h->length + extra;
    return needed <= h->capacity ? 0 : set_capacity(h, needed);
}

int history_append(ssx_history *h, double t, int micro, const double *const *outputs)
{
    if (h->length == h->capacity) {
        size_t growth = h->last_growth + h->last_growth / 2;
        growth = growth < 64 ? 64 : growth;
        if (set_capacity(h, h->capacity + growth) != 0) {
            return -1;
        }
        h->last_growth = growth;
    }
    size_t row = h->length;
    h->time[row] = t;
    h->micro[row] = micro;
    /* a plain loop: rows are a few doubles, too short to pay for a memcpy call */
    for (int c = 0; c < h->n_components; ++c) {
        size_t n = (size_t)h->columns[c];
        double *dst = h->values[c] + row * n;
        const double *src = outputs[c];
        for (size_t j = 0; j < n; ++j) {
            dst[j] = src[j];
        }
    }
    h->length++;
    return 0;
}

size_t history_bytes(const ssx_history *h)
{
    size_t per_sample = sizeof(double) + sizeof(int);
    for (int c = 0; c < h->n_components; ++c) {
        per_sample += (size_t)h->columns[c] * sizeof(double);
    }
    return h->capacity * per_sample;
}
