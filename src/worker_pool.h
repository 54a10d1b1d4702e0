/* A persistent pool of threads that run one job together: the calling thread and n workers
 * each run their share, and the call returns when every share is done. Threads are started
 * once, sleep between jobs and are joined when the pool is freed. */
#ifndef SSX_WORKER_POOL_H
#define SSX_WORKER_POOL_H

typedef struct worker_pool worker_pool;

/* One share of a job: `thread` is 0 on the calling thread, 1..n on the workers. */
typedef void (*worker_job)(void *context, int thread);

/* Starts n_workers >= 1 threads with every signal but the faults blocked (signals stay with
 * the threads the application owns). NULL when memory or a thread cannot be had; *error is
 * then the errno. */
worker_pool *worker_pool_new(int n_workers, int *error);
void worker_pool_free(worker_pool *pool);         /* joins the workers; NULL is ignored */
int worker_pool_threads(const worker_pool *pool); /* n_workers + 1 */
/* Runs job(context, k) for k = 0..n_workers, share 0 on the calling thread, and returns when
 * all have returned. In a process forked from the pool's (which has none of its threads) the
 * calling thread runs every share itself. */
void worker_pool_run(worker_pool *pool, worker_job job, void *context);
/* The share the calling thread runs: k on worker k, 0 on any thread not of the pool. */
int worker_pool_self(const worker_pool *pool);

#endif
