/* A byte stream to another process (one end of a socket pair): whole messages sent and
 * received, with deadlines, a watch on the peer process and a way to be stopped. The one place
 * that knows how the operating system moves bytes between processes (sockets, poll, waitid on
 * POSIX systems). */
#ifndef SSX_CHANNEL_H
#define SSX_CHANNEL_H

#include <stddef.h>

/* Sends head and payload (either may be empty) completely, never raising SIGPIPE.
 * Returns 0, or -1 when the peer is gone. */
int channel_send(int channel, const void *head, size_t head_size, const void *payload,
                 size_t payload_size);

typedef enum {
    CHANNEL_RECEIVED = 0,
    CHANNEL_PEER_GONE = -1,
    CHANNEL_TIMED_OUT = -2,
    CHANNEL_STOPPED = -3 /* the watch asked to stop waiting */
} channel_receive_result;

/* Asked about every 100 ms while a receive waits: nonzero stops the wait (CHANNEL_STOPPED). */
typedef struct {
    int (*stop)(void *user);
    void *user;
} channel_watch;

/* No deadline: wait as long as it takes. */
#define CHANNEL_NO_DEADLINE (-1.0)

/* Seconds on the monotonic clock (clock.h) `seconds` from now, or CHANNEL_NO_DEADLINE when
 * seconds is not positive. */
double channel_deadline_after(double seconds);

/* Receives exactly size bytes before the deadline (monotonic seconds, or CHANNEL_NO_DEADLINE).
 * peer (a process id, or 0) is checked every 100 ms while waiting, so a peer that died while
 * another process still holds its end of the channel is noticed too; so is `watch` (NULL:
 * none). */
channel_receive_result channel_receive(int channel, void *data, size_t size, double deadline,
                                       int peer, const channel_watch *watch);

/* Waits until the peer closes its end of the channel (it may close it by ending). */
void channel_wait_for_hangup(int channel);

#endif
