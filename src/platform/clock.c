/* The monotonic clock on POSIX systems (see clock.h). */
#define _POSIX_C_SOURCE 199309L

#include "clock.h"

#include <time.h>

double monotonic_seconds(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}
