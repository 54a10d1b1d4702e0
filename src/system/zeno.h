/* Chattering (Zeno): one rule for every source of events, the master's indicators and the
 * components' own events alike, and one place that decides its interval. */
#ifndef SSX_ZENO_H
#define SSX_ZENO_H

#include "system.h"

/* The shortest interval between two events that are not one event found twice: ten times the
 * localization's tolerance. Also the shortest step a probe takes after an event. */
static inline double distinct_events_interval(const ssx_hybrid_options *opt)
{
    return 10.0 * opt->tol_time;
}

/* The interval below which two events of one source are chattering, whatever else holds:
 * zeno_min_interval when set, else distinct_events_interval(). */
double zeno_min_interval(const ssx_hybrid_options *opt);

typedef enum {
    ZENO_NONE,          /* not chattering */
    ZENO_TOO_CLOSE,     /* within zeno_min_interval() of the previous event */
    ZENO_NOT_SHRINKING, /* finer than the resolution, and no longer shrinking geometrically */
} zeno_verdict;

/* Judges the interval since a source's previous event. `previous` is the interval before it
 * (INFINITY after the first two events); `resolution` is the scale below which the source's
 * events are finer than its observer resolves (for the master, a tenth of the communication
 * step); 0 when there is none. With zeno_min_interval set, that alone is the rule. Otherwise
 * events finer than the resolution are still followed while their intervals shrink
 * geometrically, the way to an accumulation point, which zeno_min_interval() then stops. */
zeno_verdict zeno_judge(const ssx_hybrid_options *opt, double interval, double previous,
                        double resolution);

#endif
