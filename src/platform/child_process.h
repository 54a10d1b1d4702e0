/* A child process connected by a socket: started, killed, reaped with the story of how it
 * ended. The one place that knows how the operating system makes processes (posix_spawn,
 * waitpid, signals on POSIX systems). */
#ifndef SSX_CHILD_PROCESS_H
#define SSX_CHILD_PROCESS_H

#include <stddef.h>

/* Starts the program argv[0] with argv, in a process group of its own (Ctrl-C at the terminal
 * is the parent's to handle), with no signal blocked and SIGPIPE at its default, and one end of
 * a new socket pair as its descriptor child_fd; *socket receives the other end. Returns 0 with
 * *pid set, or an errno value, with what it says in `error`. */
int child_process_start(char *const argv[], int child_fd, int *pid, int *socket, char *error,
                        size_t error_size);
/* Ends the child now, whatever it is doing (SIGKILL). */
void child_process_kill(int pid);
/* Ends the child's process group: the child and whatever it started (it leads the group). */
void child_process_kill_group(int pid);
/* Waits for the child to end, killing it when it does not end by itself within a second, and
 * says how it ended ("died of signal 11 (SIGSEGV, Segmentation fault)"). */
void child_process_reap(int pid, char *how, size_t how_size);
/* Closes the parent's end of the socket: a child reading it sees the end. */
void child_process_close_socket(int socket);

#endif
