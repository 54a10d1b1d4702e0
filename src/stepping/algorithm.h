/* Master algorithms: how the whole system advances over one communication step. One is chosen
 * at ssx_initialize from what the system holds; the time loop calls it and never asks which it
 * is. A new algorithm (a parallel Jacobi) is one more row of the table in algorithm.c. */
#ifndef SSX_ALGORITHM_H
#define SSX_ALGORITHM_H

#include "syssimx_engine.h"

typedef struct ssx_master_algorithm {
    /* Makes the algorithm's own state for the system as built into *workspace, which the
     * system holds for it (sys->algorithm_workspace) until release. NULL: it keeps none. */
    int (*prepare)(ssx_system *sys, void **workspace);
    /* Advances from `from` inside the communication step [t, t_next] (from is t unless an
     * event ended the step's last call) and records what it completes. Returns at t_next, or
     * right after an event instant an indicator made is handled (*event set, sys->time the
     * instant; the grid point is not recorded when the instant is t_next itself). */
    int (*step)(ssx_system *sys, double t, double from, double t_next, int *event);
    /* Frees what prepare made. NULL: prepare makes nothing to free. */
    void (*release)(ssx_system *sys, void *workspace);
    /* What it carries from one step to the next beyond the system's values (a saved state,
     * saved_state.c): into carried[ALGORITHM_CARRIED] and back. NULL: nothing. */
    void (*carry_out)(const ssx_system *sys, double *carried);
    void (*carry_in)(ssx_system *sys, const double *carried);
} ssx_master_algorithm;

enum { ALGORITHM_CARRIED = 3 };

/* Chooses the system's algorithm and prepares it, releasing the one before: hybrid when the
 * system steps so that it can roll back (sys->stepping_hybrid: it has event indicators, or it
 * locates its output clocks' ticks). */
int master_algorithm_choose(ssx_system *sys);
/* Releases the system's algorithm and its state (ssx_system_free). */
void master_algorithm_release(ssx_system *sys);

#endif
