/* What worker threads must know of signals and processes: Ctrl-C and timers belong to the
 * application's own threads, and a pool copied into a forked child has no threads. */
#ifndef SSX_THREAD_SIGNALS_H
#define SSX_THREAD_SIGNALS_H

/* Runs start(context) with every asynchronous signal blocked on the calling thread, so that
 * the threads it creates inherit that mask (faults such as SIGSEGV stay deliverable to the
 * handlers installed for an FMU); the mask is restored before returning start's result. */
int with_asynchronous_signals_blocked(int (*start)(void *context), void *context);
/* The calling process's id, to tell a forked copy from the process that made a pool. */
long current_process_id(void);

#endif
