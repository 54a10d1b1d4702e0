/* Socket I/O for the isolated FMU: retried on EINTR and partial transfers. */
#define _DEFAULT_SOURCE

#include "remote_io.h"

#include <errno.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <sys/wait.h>

int remote_send(int fd, const void *head, size_t head_size, const void *payload,
                size_t payload_size)
{
    struct iovec parts[2] = {{(void *)head, head_size}, {(void *)payload, payload_size}};
    struct iovec *part = parts;
    size_t n_parts = payload_size > 0 ? 2 : 1;
    while (n_parts > 0) {
        struct msghdr message = {.msg_iov = part, .msg_iovlen = n_parts};
        ssize_t sent = sendmsg(fd, &message, MSG_NOSIGNAL);
        if (sent < 0) {
            if (errno == EINTR) {
                continue;
            }
            return -1;
        }
        size_t left = (size_t)sent;
        while (n_parts > 0 && left >= part->iov_len) {
            left -= part->iov_len;
            ++part;
            --n_parts;
        }
        if (n_parts > 0) {
            part->iov_base = (char *)part->iov_base + left;
            part->iov_len -= left;
        }
    }
    return 0;
}

/* Milliseconds from now to the deadline, at least 0, at most the peer check interval. */
static int wait_slice(const struct timespec *deadline, int peer, int watched)
{
    int slice = peer > 0 || watched ? 100 : -1;
    if (deadline == NULL) {
        return slice;
    }
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    double left = (double)(deadline->tv_sec - now.tv_sec) * 1e3 +
                  (double)(deadline->tv_nsec - now.tv_nsec) * 1e-6;
    int remaining = left <= 0.0 ? 0 : left >= 1e9 ? 1000000000 : (int)left + 1;
    return slice < 0 || remaining < slice ? remaining : slice;
}

static int expired(const struct timespec *deadline)
{
    if (deadline == NULL) {
        return 0;
    }
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return now.tv_sec > deadline->tv_sec ||
           (now.tv_sec == deadline->tv_sec && now.tv_nsec >= deadline->tv_nsec);
}

/* Whether the peer process has ended, without reaping it (its exit status stays readable). */
static int peer_ended(int peer)
{
    siginfo_t info = {0};
    if (waitid(P_PID, (id_t)peer, &info, WEXITED | WNOHANG | WNOWAIT) != 0) {
        return errno == ECHILD;
    }
    return info.si_pid == peer;
}

remote_receive_result remote_receive(int fd, void *data, size_t size,
                                     const struct timespec *deadline, int peer)
{
    return remote_receive_watched(fd, data, size, deadline, peer, NULL);
}

remote_receive_result remote_receive_watched(int fd, void *data, size_t size,
                                             const struct timespec *deadline, int peer,
                                             const remote_watch *watch)
{
    int watched = watch != NULL && watch->stop != NULL;
    char *at = data;
    while (size > 0) {
        ssize_t got = recv(fd, at, size, MSG_DONTWAIT);
        if (got > 0) {
            at += got;
            size -= (size_t)got;
            continue;
        }
        if (got == 0) {
            return PEER_GONE;
        }
        if (errno == EINTR) {
            continue;
        }
        if (errno != EAGAIN && errno != EWOULDBLOCK) {
            return PEER_GONE;
        }
        if (expired(deadline)) {
            return TIMED_OUT;
        }
        struct pollfd readable = {.fd = fd, .events = POLLIN};
        int ready = poll(&readable, 1, wait_slice(deadline, peer, watched));
        if (ready < 0 && errno != EINTR) {
            return PEER_GONE;
        }
        if (ready == 0 && peer > 0 && peer_ended(peer)) {
            return PEER_GONE;
        }
        if (ready == 0 && watched && watch->stop(watch->user) != 0) {
            return STOPPED;
        }
    }
    return RECEIVED;
}
