/* The monotonic clock: seconds that only ever go forward, for timing and deadlines. */
#ifndef SSX_CLOCK_H
#define SSX_CLOCK_H

double monotonic_seconds(void);

#endif
