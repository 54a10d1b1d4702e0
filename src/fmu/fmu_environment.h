/* What an FMU's callbacks reach through the environment pointer the back-end hands the FMU:
 * where its log messages go, and, for an FMU run by a host process, that host. The binding
 * owns one per FMU; the back-ends and the forwarding functions of isolation use it without
 * knowing the binding.
 *
 * An FMU hands the environment back to its callbacks, and some hand back something else (1, 2,
 * NULL, another instance's): a callback never reads through the pointer it is handed before
 * checking it against the environment of the FMU call in progress on its thread, which the
 * binding marks around every call (ssx_fmu_environment_enter). */
#ifndef SSX_FMU_ENVIRONMENT_H
#define SSX_FMU_ENVIRONMENT_H

typedef struct ssx_remote ssx_remote;

enum { SSX_FMU_MESSAGE_SIZE = 1024 }; /* the longest message kept, with its NUL */

typedef struct {
    ssx_remote *remote; /* an isolated FMU's host process; NULL when the binary runs here */
    /* what the back-end handed the FMU as its callbacks' environment: this environment (FMI
     * 2.0) or the back-end's context (FMI 3.0); the pointer a callback's argument must equal */
    const void *handed;
    char last_message[SSX_FMU_MESSAGE_SIZE];
} ssx_fmu_environment;

/* The binding's mark of the FMU call in progress on this thread: entered before a call into
 * the FMU, left after it. Calls do not nest (the engine calls no FMU from an FMU's callback). */
void ssx_fmu_environment_enter(ssx_fmu_environment *environment);
void ssx_fmu_environment_leave(void);

/* The environment of the FMU call in progress on this thread, NULL between calls. */
ssx_fmu_environment *ssx_fmu_environment_calling(void);

/* The environment of the call in progress when `claimed` (what a callback was handed) is the
 * one it was handed, else NULL: the pointer is compared, never read. */
ssx_fmu_environment *ssx_fmu_environment_claimed(const void *claimed);

/* Keeps `text`, which an FMU logged, as the last message of `logging`, its environment
 * (ssx_fmu_environment_claimed). A message whose environment is unknown (NULL) is kept too, as
 * the last message of the FMU being called, attributed to "an FMU"; outside any call it goes
 * to stderr. */
void ssx_fmu_environment_log(ssx_fmu_environment *logging, const char *text);

#endif
