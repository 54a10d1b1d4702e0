/* Reading the clock costs about as much as a cheap macro step, so the monitor reads it every
 * `stride` steps and sizes the stride from the last readings to about a tenth of the
 * interval: a Ctrl-C waits at most about one interval plus one stride. */
#include "monitor.h"

#include "clock.h"
#include "syssimx_engine.h"

enum { MAX_STRIDE = 1 << 20 };

void monitor_start(ssx_monitor *m)
{
    m->stride = 1;
    m->countdown = 1;
    m->last_reading = monotonic_seconds();
    if (!m->batch) {
        m->last_call = m->last_reading;
    }
    m->running = 1;
}

void monitor_batch_start(ssx_monitor *m)
{
    m->batch = 1;
    m->last_call = monotonic_seconds();
}

void monitor_batch_end(ssx_monitor *m)
{
    m->batch = 0;
}

void monitor_stop(ssx_monitor *m)
{
    m->running = 0;
}

/* The stride that would have taken `target` seconds at the pace of the last one: at most
 * twice the last stride (a pace measured over few steps is noisy), at least one step. */
static long next_stride(long stride, double elapsed, double target)
{
    double steps = elapsed > 0.0 ? (double)stride * target / elapsed : 2.0 * (double)stride;
    if (steps > 2.0 * (double)stride) {
        steps = 2.0 * (double)stride;
    }
    if (steps > MAX_STRIDE) {
        steps = MAX_STRIDE;
    }
    return steps < 1.0 ? 1 : (long)steps;
}

int monitor_check(ssx_monitor *m, double t)
{
    const double interval = SSX_MONITOR_INTERVAL_MS * 1e-3;
    double now = monotonic_seconds();
    m->stride = next_stride(m->stride, now - m->last_reading, interval / 10.0);
    m->countdown = m->stride;
    m->last_reading = now;
    if (now - m->last_call < interval) {
        return 0;
    }
    m->last_call = now;
    return m->call(m->user, t);
}
