/* The memory of each member's step, fetched ahead. A cheap FMU steps in less time than a trip
 * to memory takes; where thousands step in turn, what each member's step reads first (its
 * component block, its links, its FMU binding) lies far from the member before it and misses
 * every cache. The lines' addresses, gathered in schedule order when the system initializes,
 * sit in one dense table: the step of the member at position k asks for those of the member at
 * k + MEMBER_PREFETCH_AHEAD, which arrive while the members between step. */
#ifndef SSX_MEMBER_PREFETCH_H
#define SSX_MEMBER_PREFETCH_H

#include "system.h"

/* Far enough ahead that the lines arrive before the member steps (a few cheap steps cover a
 * trip to memory), near enough that they are still cached when it does. */
enum { MEMBER_PREFETCH_AHEAD = 4, MEMBER_PREFETCH_LINES = 8 };

/* The cache lines of one member, in schedule order: one table row per cache line of 64 bytes. */
struct member_lines {
    const void *line[MEMBER_PREFETCH_LINES];
};

/* Builds the table for the schedule as prepared (coupling_prepare); 0, or -1 with the error
 * set. */
int member_prefetch_prepare(ssx_system *sys);
void member_prefetch_free(ssx_system *sys);

/* Asks for the lines of the member at schedule position `position`, if there is one. */
static inline void member_prefetch(const ssx_system *sys, int position)
{
#if defined(__GNUC__) || defined(__clang__)
    if (position < sys->n_components && sys->member_lines != NULL) {
        const struct member_lines *m = &sys->member_lines[position];
        for (int i = 0; i < MEMBER_PREFETCH_LINES; ++i) {
            __builtin_prefetch(m->line[i]);
        }
    }
#else
    (void)sys;
    (void)position; /* a compiler without the builtin steps without fetching ahead */
#endif
}

#endif
