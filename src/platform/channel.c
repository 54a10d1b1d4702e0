/* A byte stream between processes on POSIX systems (see channel.h): a socket, retried on EINTR
 * and partial transfers. */
#define _GNU_SOURCE /* POLLRDHUP */

#include "channel.h"

#include <errno.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <sys/wait.h>

#include "clock.h"

int channel_send(int channel, const void *head, size_t head_size, const void *payload,
                 size_t payload_size)
{
    struct iovec parts[2] = {{(void *)head, head_size}, {(void *)payload, payload_size}};
    struct iovec *part = parts;
    size_t n_parts = payload_size > 0 ? 2 : 1;
    while (n_parts > 0) {
        struct msghdr message = {.msg_iov = part, .msg_iovlen = n_parts};
        ssize_t sent = sendmsg(channel, &message, MSG_NOSIGNAL);
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

double channel_deadline_after(double seconds)
{
    return seconds > 0.0 ? monotonic_seconds() + seconds : CHANNEL_NO_DEADLINE;
}

static int has_deadline(double deadline)
{
    return deadline >= 0.0;
}

/* Milliseconds from now to the deadline, at least 0, at most the peer check interval. */
static int wait_slice(double deadline, int peer, int watched)
{
    int slice = peer > 0 || watched ? 100 : -1;
    if (!has_deadline(deadline)) {
        return slice;
    }
    double left = (deadline - monotonic_seconds()) * 1e3;
    int remaining = left <= 0.0 ? 0 : left >= 1e9 ? 1000000000 : (int)left + 1;
    return slice < 0 || remaining < slice ? remaining : slice;
}

static int expired(double deadline)
{
    return has_deadline(deadline) && monotonic_seconds() >= deadline;
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

channel_receive_result channel_receive(int channel, void *data, size_t size, double deadline,
                                       int peer, const channel_watch *watch)
{
    int watched = watch != NULL && watch->stop != NULL;
    char *at = data;
    while (size > 0) {
        ssize_t got = recv(channel, at, size, MSG_DONTWAIT);
        if (got > 0) {
            at += got;
            size -= (size_t)got;
            continue;
        }
        if (got == 0) {
            return CHANNEL_PEER_GONE;
        }
        if (errno == EINTR) {
            continue;
        }
        if (errno != EAGAIN && errno != EWOULDBLOCK) {
            return CHANNEL_PEER_GONE;
        }
        if (expired(deadline)) {
            return CHANNEL_TIMED_OUT;
        }
        struct pollfd readable = {.fd = channel, .events = POLLIN};
        int ready = poll(&readable, 1, wait_slice(deadline, peer, watched));
        if (ready < 0 && errno != EINTR) {
            return CHANNEL_PEER_GONE;
        }
        if (ready == 0 && peer > 0 && peer_ended(peer)) {
            return CHANNEL_PEER_GONE;
        }
        if (ready == 0 && watched && watch->stop(watch->user) != 0) {
            return CHANNEL_STOPPED;
        }
    }
    return CHANNEL_RECEIVED;
}

void channel_wait_for_hangup(int channel)
{
    struct pollfd hangup = {.fd = channel, .events = POLLRDHUP};
    while (poll(&hangup, 1, -1) < 0 || (hangup.revents & (POLLRDHUP | POLLHUP)) == 0) {
    }
}
