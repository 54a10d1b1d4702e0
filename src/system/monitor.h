/* The wall-clock monitor of a run: a callback about every SSX_MONITOR_INTERVAL_MS, with the
 * clock read only every `stride` macro steps so that a cheap step pays a decrement. */
#ifndef SSX_MONITOR_H
#define SSX_MONITOR_H

#include <stddef.h>

typedef struct {
    int (*call)(void *user, double t); /* NULL: no monitor */
    void *user;
    long stride;        /* macro steps between two clock readings */
    long countdown;     /* macro steps left until the next reading */
    double last_reading; /* seconds on the monotonic clock */
    double last_call;
    int running;        /* between monitor_start and monitor_stop: a run is on */
    int batch;          /* between monitor_batch_start and _end: runs follow each other */
} ssx_monitor;

/* At the start of a run: the stride starts afresh, and the interval too unless the run is one
 * of a batch. */
void monitor_start(ssx_monitor *m);
/* Around runs made one after another in one engine call (an ensemble's members): the
 * interval runs on over them, so a monitor is called although no single run lasts an
 * interval. */
void monitor_batch_start(ssx_monitor *m);
void monitor_batch_end(ssx_monitor *m);
/* At the end of a run: nothing asks the monitor until the next starts (ssx_initialize's
 * loops run with the last run's deadline long past). */
void monitor_stop(ssx_monitor *m);
/* Reads the clock, resizes the stride and calls the monitor when the interval has passed. */
int monitor_check(ssx_monitor *m, double t);
/* After each macro step, reached time t: 0 to go on, nonzero when the monitor stops the run. */
static inline int monitor_after_step(ssx_monitor *m, double t)
{
    return m->call != NULL && --m->countdown <= 0 ? monitor_check(m, t) : 0;
}

#endif
