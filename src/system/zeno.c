/* Chattering (see zeno.h). */
#include "zeno.h"

/* Event intervals that shrink at least this much each are on their way to an accumulation
 * point (a bouncing ball's shrink by its restitution). */
#define GEOMETRIC_APPROACH 0.9

double zeno_min_interval(const ssx_hybrid_options *opt)
{
    return opt->zeno_min_interval > 0.0 ? opt->zeno_min_interval
                                        : distinct_events_interval(opt);
}

zeno_verdict zeno_judge(const ssx_hybrid_options *opt, double interval, double previous,
                        double resolution)
{
    if (interval < zeno_min_interval(opt)) {
        return ZENO_TOO_CLOSE;
    }
    if (opt->zeno_min_interval > 0.0) {
        return ZENO_NONE;
    }
    return interval < resolution && !(interval <= GEOMETRIC_APPROACH * previous)
               ? ZENO_NOT_SHRINKING
               : ZENO_NONE;
}
