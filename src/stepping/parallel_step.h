/* Stepping components on the system's threads (ssx_set_threads). A batch is a list of
 * components that may step in any order: none feeds another within the step (all of a Jacobi
 * step; a run of Gauss-Seidel groups, or one loop's members). The FMU components of a batch
 * that may leave the calling thread step on the pool's threads, which claim them in order as
 * they get free (the calling thread always takes part, so it never waits for a worker that is
 * not running); the rest (Python-backed components, table sources, FMUs that declare
 * canBeInstantiatedOnlyOncePerProcess, FMUs used by two components) step on the
 * calling thread. Each thread reports its first failure and termination request in a record
 * of its own; after the join the calling thread replays the batch in component order, so the
 * statistics, the termination and the reported error are those of one thread. */
#ifndef SSX_PARALLEL_STEP_H
#define SSX_PARALLEL_STEP_H

#include "system.h"

typedef struct parallel_plan parallel_plan;

/* A batch of Gauss-Seidel: sys->order[first .. first + size); group >= 0 when the batch is
 * that loop group's members, whose loop is solved after them. */
typedef struct {
    int first;
    int size;
    int group;
} parallel_batch;

/* At ssx_initialize, after the schedule is known: builds sys->parallel for sys->threads > 1
 * (keeping the pool when its size is unchanged), frees it for 1. */
int parallel_prepare(ssx_system *sys);
void parallel_free(parallel_plan *plan);
/* The Gauss-Seidel batches of the schedule, in order. */
int parallel_batches(const parallel_plan *plan, const parallel_batch **batches);
/* How one member is written and stepped from t to t + h on the calling thread (the
 * coupling's). */
typedef int (*member_step)(ssx_system *sys, ssx_component *c, double t, double h);
/* Writes and steps components[members[0..n)] from t to t + h, the first failure in member
 * order reported as if they had stepped one by one. Without a plan: one by one, by
 * step_member. */
int parallel_step(ssx_system *sys, const int *members, int n, double t, double h,
                  member_step step_member);

#endif
