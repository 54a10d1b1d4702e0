/* Where an FMU's log messages go, and which FMU is being called on this thread. */
#include "fmu_environment.h"

#include <stdio.h>

/* The FMI 2.0 and 3.0 loggers are handed nothing but the pointer the FMU chooses to pass, and
 * checking a pointer without reading through it needs a record of what was handed out. A
 * process-wide table of live environments would be shared state behind a lock; the FMU that
 * logs, though, is the one this thread is calling (a message logged during a call comes from
 * the thread that made it). So each thread records, for the length of one call, which
 * environment it is calling: like errno, the thread's own, never shared and never locked.
 * The initial-exec model reaches it without the dynamic loader's __tls_get_addr, so that a
 * binary built from the engine (an exported FMU) needs libc and libm only. */
static _Thread_local ssx_fmu_environment *calling __attribute__((tls_model("initial-exec")));

void ssx_fmu_environment_enter(ssx_fmu_environment *environment)
{
    calling = environment;
}

void ssx_fmu_environment_leave(void)
{
    calling = NULL;
}

ssx_fmu_environment *ssx_fmu_environment_calling(void)
{
    return calling;
}

ssx_fmu_environment *ssx_fmu_environment_claimed(const void *claimed)
{
    return calling != NULL && claimed != NULL && claimed == calling->handed ? calling : NULL;
}

void ssx_fmu_environment_log(ssx_fmu_environment *logging, const char *text)
{
    if (logging != NULL) {
        snprintf(logging->last_message, sizeof logging->last_message, "%s", text);
    } else if (calling != NULL) {
        snprintf(calling->last_message, sizeof calling->last_message, "an FMU: %s", text);
    } else {
        /* no FMU call on this thread (the FMU logs from a thread of its own): no FMU to keep
         * it for */
        fprintf(stderr, "syssimx: an FMU logged: %s\n", text);
    }
}
