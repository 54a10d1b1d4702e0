/* Child processes on POSIX systems (see child_process.h). */
#define _DEFAULT_SOURCE

#include "child_process.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

static int spawn(char *const argv[], int child_end, int child_fd, pid_t *pid)
{
    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attributes;
    if (posix_spawn_file_actions_init(&actions) != 0) {
        return ENOMEM;
    }
    if (posix_spawnattr_init(&attributes) != 0) {
        posix_spawn_file_actions_destroy(&actions);
        return ENOMEM;
    }
    sigset_t no_signals, default_signals;
    sigemptyset(&no_signals);
    sigemptyset(&default_signals);
    sigaddset(&default_signals, SIGPIPE);
    int failed = posix_spawn_file_actions_adddup2(&actions, child_end, child_fd) ||
                 posix_spawnattr_setpgroup(&attributes, 0) ||
                 posix_spawnattr_setsigmask(&attributes, &no_signals) ||
                 posix_spawnattr_setsigdefault(&attributes, &default_signals) ||
                 posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP |
                                                           POSIX_SPAWN_SETSIGMASK |
                                                           POSIX_SPAWN_SETSIGDEF);
    if (!failed) {
        failed = posix_spawn(pid, argv[0], &actions, &attributes, argv, environ);
    }
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    return failed;
}

int child_process_start(char *const argv[], int child_fd, int *pid, int *socket, char *error,
                        size_t error_size)
{
    int pair[2];
    /* close-on-exec on both ends: only the child gets its end, as child_fd */
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) != 0) {
        int failed = errno;
        snprintf(error, error_size, "cannot create a socket: %s", strerror(failed));
        return failed;
    }
    if (pair[1] == child_fd) { /* dup2 onto itself would keep close-on-exec */
        int moved = fcntl(pair[1], F_DUPFD_CLOEXEC, child_fd + 1);
        close(pair[1]);
        pair[1] = moved;
    }
    pid_t child = 0;
    int failed = pair[1] < 0 ? errno : spawn(argv, pair[1], child_fd, &child);
    if (pair[1] >= 0) {
        close(pair[1]);
    }
    if (failed) {
        close(pair[0]);
        snprintf(error, error_size, "cannot start %s: %s", argv[0], strerror(failed));
        return failed;
    }
    *pid = (int)child;
    *socket = pair[0];
    return 0;
}

void child_process_kill(int pid)
{
    kill((pid_t)pid, SIGKILL);
}

void child_process_kill_group(int pid)
{
    kill(-(pid_t)pid, SIGKILL);
}

static const char *signal_name(int signal)
{
    switch (signal) {
    case SIGSEGV: return "SIGSEGV";
    case SIGABRT: return "SIGABRT";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    default: return "signal";
    }
}

void child_process_reap(int pid, char *how, size_t how_size)
{
    int status = 0;
    pid_t done = 0;
    for (int tries = 0; tries < 100 && done == 0; ++tries) {
        done = waitpid((pid_t)pid, &status, WNOHANG);
        if (done == 0) {
            nanosleep(&(struct timespec){0, 10000000}, NULL);
        }
    }
    if (done == 0) {
        kill((pid_t)pid, SIGKILL);
        done = waitpid((pid_t)pid, &status, 0);
    }
    if (done != (pid_t)pid) {
        snprintf(how, how_size, "ended (its exit status is unknown: %s)", strerror(errno));
    } else if (WIFSIGNALED(status)) {
        snprintf(how, how_size, "died of signal %d (%s, %s)", WTERMSIG(status),
                 signal_name(WTERMSIG(status)), strsignal(WTERMSIG(status)));
    } else {
        snprintf(how, how_size, "exited with status %d", WEXITSTATUS(status));
    }
}

void child_process_close_socket(int socket)
{
    close(socket);
}
