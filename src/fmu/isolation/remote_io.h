/* Whole-message I/O on the socket between the engine and the FMU host process. */
#ifndef SSX_REMOTE_IO_H
#define SSX_REMOTE_IO_H

#include <stddef.h>
#include <time.h>

/* Sends head and payload (either may be empty) completely, never raising SIGPIPE.
 * Returns 0, or -1 when the peer is gone. */
int remote_send(int fd, const void *head, size_t head_size, const void *payload,
                size_t payload_size);

typedef enum {
    RECEIVED = 0,
    PEER_GONE = -1,
    TIMED_OUT = -2,
    STOPPED = -3 /* the watch asked to stop waiting */
} remote_receive_result;

/* Asked about every 100 ms while a receive waits: nonzero stops the wait (STOPPED). */
typedef struct {
    int (*stop)(void *user);
    void *user;
} remote_watch;

/* Receives exactly size bytes. deadline (CLOCK_MONOTONIC) may be NULL: wait as long as it
 * takes. peer (a process id, or 0) is checked every 100 ms while waiting, so a peer that died
 * while another process still holds its end of the socket is noticed too. */
remote_receive_result remote_receive(int fd, void *data, size_t size,
                                     const struct timespec *deadline, int peer);
/* remote_receive that also asks `watch` (NULL: none) while it waits. */
remote_receive_result remote_receive_watched(int fd, void *data, size_t size,
                                             const struct timespec *deadline, int peer,
                                             const remote_watch *watch);

#endif
