/* A persistent pool of threads that step the tasks of one job together: the calling thread
 * and whichever workers are awake claim the tasks in order, and the call returns when every
 * task is done. Threads are started once, sleep between jobs and are joined when the pool is
 * freed. */
#ifndef SSX_WORKER_POOL_H
#define SSX_WORKER_POOL_H

typedef struct worker_pool worker_pool;

/* One task of a job: `thread` is 0 on the calling thread, 1..n on the workers. */
typedef void (*worker_task)(void *context, int task, int thread);

/* Starts n_workers >= 1 threads with every signal but the faults blocked (signals stay with
 * the threads the application owns). NULL when memory or a thread cannot be had; *error is
 * then the errno. */
worker_pool *worker_pool_new(int n_workers, int *error);
void worker_pool_free(worker_pool *pool);         /* joins the workers; NULL is ignored */
int worker_pool_threads(const worker_pool *pool); /* n_workers + 1 */
/* Runs task(context, k, thread) once for every k in 0 .. n_tasks - 1 and returns when all
 * have returned. The calling thread runs task 0 and claims the next free task after each;
 * a worker joins when it wakes and claims the same way. So the caller never waits for a
 * worker that is not running: it waits only for the tasks workers have claimed. In a process
 * forked from the pool's (which has none of its threads) the caller runs every task. */
void worker_pool_run(worker_pool *pool, worker_task task, void *context, int n_tasks);
/* The thread the caller is: k on worker k, 0 on any thread not of the pool. */
int worker_pool_self(const worker_pool *pool);

#endif
