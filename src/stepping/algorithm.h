/* Master algorithms: how the whole system advances over one communication step. One is chosen
 * at ssx_initialize from what the system holds; the time loop calls it and never asks which it
 * is. A new algorithm (a parallel Jacobi) is one more row of the table in algorithm.c. */
#ifndef SSX_ALGORITHM_H
#define SSX_ALGORITHM_H

#include "syssimx_engine.h"

typedef struct {
    /* Sets up the algorithm's workspace for the system as built; NULL when it needs none. */
    int (*prepare)(ssx_system *sys);
    /* Advances from t to the communication point t_next and records what it completes. */
    int (*step)(ssx_system *sys, double t, double t_next);
} ssx_master_algorithm;

/* Chooses the system's algorithm and prepares it: hybrid when it has event indicators. */
int master_algorithm_choose(ssx_system *sys);

#endif
