/* An FMU binary run in a host process of its own (fmu_host.c), seen by the FMU binding as a
 * table of fmi2 functions that forward each call over a socket. */
#ifndef SSX_FMU_REMOTE_H
#define SSX_FMU_REMOTE_H

#include <stddef.h>

typedef struct ssx_remote ssx_remote;

/* Starts the host process on the binary and learns which functions it exports: fmi2 ones, or
 * with fmi1 nonzero those of FMI 1.0 Co-Simulation (ssx_remote_function then forwards them).
 * call_timeout > 0: an fmi2 call that has not returned after that many seconds kills the host
 * (the call fails with fmi2Fatal). On failure returns NULL and writes the reason into error. */
ssx_remote *ssx_remote_start(const char *host_path, const char *binary_path,
                             const char *model_identifier, int fmi1, double call_timeout,
                             char *error, size_t error_size);
/* Ends the host process (waits for it: nothing is left behind) and frees the remote. */
void ssx_remote_stop(ssx_remote *remote);

/* Ends the current host, whatever it is doing, so that the next fmi2Instantiate starts a new
 * one: how an isolated FMU recovers from fmi2Fatal without calling the broken instance again. */
void ssx_remote_restart(ssx_remote *remote);

/* While a call waits for the host, stop(user) is asked about every 100 ms (stop NULL: never);
 * nonzero kills the host and its process group, and the call fails with fmi2Fatal. The engine
 * sets it for a run, so that Ctrl-C and a run's timeout reach an FMU stuck in a call. */
void ssx_remote_set_watch(ssx_remote *remote, int (*stop)(void *user), void *user);

/* The forwarding implementation of the fmi2 function `name` (FMI 1.0: the fmi one), as dlsym
 * would return it, or NULL when the binary does not export it or it is not forwarded (FMI
 * 1.0's fmiGetRealStatus, fmiGetString and fmiSetString). The instance fmi2Instantiate returns
 * is the remote itself; its callbacks' componentEnvironment must be the ssx_fmu_environment
 * (fmu_environment.h) that holds the remote: FMI 2.0 hands fmi2Instantiate nothing else to
 * find it by (FMI 1.0 hands none: fmiInstantiateSlave finds it as the environment the binding
 * is calling). A host that dies makes the call fail with fmi2Fatal and logs why (the signal,
 * or the timeout); the next fmi2Instantiate starts a new host. */
void *ssx_remote_function(const ssx_remote *remote, const char *name);

#endif
