/* The recorded history: one time axis with its micro index, and per component a row-major
 * matrix of output values. */
#ifndef SSX_HISTORY_H
#define SSX_HISTORY_H

#include <stddef.h>

typedef struct {
    size_t length;
    size_t capacity;
    size_t last_growth; /* rows added by the last unplanned growth */
    double *time;
    int *micro;
    int n_components;
    int *columns;     /* outputs per component, fixed when the history starts */
    double **values;  /* per component: capacity x columns */
} ssx_history;

void history_free(ssx_history *h);
/* Drops every sample and fixes the matrix shapes from the given output counts. */
int history_start(ssx_history *h, int n_components, const int *columns);
/* Makes room for exactly `extra` more samples (no slack): used for the known grid. */
int history_reserve(ssx_history *h, size_t extra);
/* Appends one sample. Only samples beyond the reserved grid (events, trials) can find it full;
 * the room for them then grows by about 1.5x each time, so the slack stays proportional to the
 * event samples, not to the whole history. */
int history_append(ssx_history *h, double t, int micro, const double *const *outputs);
size_t history_bytes(const ssx_history *h);

#endif
