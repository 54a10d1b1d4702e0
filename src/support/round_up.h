/* Sizes rounded up to a multiple (an alignment, a cache line, a page): what every allocator of
 * the engine that lays blocks side by side computes. */
#ifndef SSX_ROUND_UP_H
#define SSX_ROUND_UP_H

#include <stddef.h>

/* The smallest multiple of `to` (positive) that is at least `size`. */
static inline size_t round_up(size_t size, size_t to)
{
    return (size + to - 1) / to * to;
}

#endif
