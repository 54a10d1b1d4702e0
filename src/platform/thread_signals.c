#include "thread_signals.h"

#include <pthread.h>
#include <signal.h>
#include <stddef.h>
#include <unistd.h>

int with_asynchronous_signals_blocked(int (*start)(void *context), void *context)
{
    sigset_t asynchronous, previous;
    sigfillset(&asynchronous);
    const int faults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS, SIGABRT};
    for (size_t i = 0; i < sizeof faults / sizeof faults[0]; ++i) {
        sigdelset(&asynchronous, faults[i]);
    }
    pthread_sigmask(SIG_SETMASK, &asynchronous, &previous);
    int status = start(context);
    pthread_sigmask(SIG_SETMASK, &previous, NULL);
    return status;
}

long current_process_id(void)
{
    return (long)getpid();
}
