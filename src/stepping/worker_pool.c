/* The pool's handshake. A job is published as one 64-bit word, the task count in the high half
 * and the next task to claim in the low half, so a claim is one compare-and-swap that also
 * tells whether the job has tasks left; `generation` advances once per job (under the lock, with a
 * broadcast, so a sleeping worker cannot miss it). A thread counts itself `busy` before it
 * claims and uncounts itself after its last task: once the caller has claimed past the end,
 * a busy count of zero means every claimed task is done. A worker that wakes late finds no
 * task left, or takes part in the job posted since, whose context is then valid. Between two
 * jobs of a run a worker and the caller poll for a short while before they sleep: a macro
 * step of cheap FMUs lasts microseconds, and waking a sleeping thread costs about as much. */
#define _POSIX_C_SOURCE 200809L

#include "worker_pool.h"

#include <errno.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "thread_signals.h"

/* Polls before sleeping: a few microseconds of one core. */
enum { SPIN_POLLS = 2000 };

typedef struct {
    worker_pool *pool;
    int thread;
} worker_start;

struct worker_pool {
    pthread_mutex_t lock;
    pthread_cond_t job_posted;
    pthread_cond_t idle;
    atomic_ulong generation;     /* advanced once per job */
    atomic_uint_least64_t claim; /* task count << 32 | next task */
    atomic_int busy;             /* threads that may still be running a task */
    atomic_int stopping;
    worker_task task;
    void *context;
    int n_workers;
    long owner; /* the process whose threads these are */
    int started; /* workers started (all of them once worker_pool_new returned it) */
    pthread_t *threads;
    worker_start *starts;
};

static int posted_since(worker_pool *pool, unsigned long seen)
{
    return atomic_load_explicit(&pool->generation, memory_order_acquire) != seen;
}

/* Claims the next tasks: a share of what is left (half of it split over the threads, at least
 * one task), so a batch of many cheap tasks costs a few claims, and the last claims are
 * small enough to even out the threads. Returns how many, from *first; 0 when none is left. */
static int claim_tasks(worker_pool *pool, int *first)
{
    uint_least64_t claim = atomic_load(&pool->claim);
    for (;;) {
        uint_least64_t next = claim & UINT32_MAX;
        uint_least64_t count = claim >> 32;
        if (next >= count) {
            return 0;
        }
        uint_least64_t share = (count - next) / (2 * (uint_least64_t)(pool->n_workers + 1));
        share = share > 0 ? share : 1;
        if (atomic_compare_exchange_weak(&pool->claim, &claim, claim + share)) {
            *first = (int)next;
            return (int)share;
        }
    }
}

/* Claims and runs tasks until none is left. */
static void take_tasks(worker_pool *pool, int thread)
{
    int first = 0;
    for (int n = claim_tasks(pool, &first); n > 0; n = claim_tasks(pool, &first)) {
        for (int k = first; k < first + n; ++k) {
            pool->task(pool->context, k, thread);
        }
    }
}

static void leave(worker_pool *pool)
{
    if (atomic_fetch_sub(&pool->busy, 1) == 1) {
        pthread_mutex_lock(&pool->lock);
        pthread_cond_signal(&pool->idle);
        pthread_mutex_unlock(&pool->lock);
    }
}

static void *worker_main(void *argument)
{
    const worker_start *start = argument;
    worker_pool *pool = start->pool;
    unsigned long seen = 0;
    for (;;) {
        for (int poll = 0; poll < SPIN_POLLS && !posted_since(pool, seen); ++poll) {
        }
        if (!posted_since(pool, seen)) {
            pthread_mutex_lock(&pool->lock);
            while (!posted_since(pool, seen)) {
                pthread_cond_wait(&pool->job_posted, &pool->lock);
            }
            pthread_mutex_unlock(&pool->lock);
        }
        seen = atomic_load_explicit(&pool->generation, memory_order_acquire);
        if (atomic_load_explicit(&pool->stopping, memory_order_acquire)) {
            return NULL;
        }
        atomic_fetch_add(&pool->busy, 1);
        take_tasks(pool, start->thread);
        leave(pool);
    }
}

/* Advances the generation so that every worker wakes up to the job (or to stopping). */
static void post(worker_pool *pool)
{
    pthread_mutex_lock(&pool->lock);
    atomic_fetch_add_explicit(&pool->generation, 1, memory_order_acq_rel);
    pthread_cond_broadcast(&pool->job_posted);
    pthread_mutex_unlock(&pool->lock);
}

static void stop_workers(worker_pool *pool, int started)
{
    atomic_store_explicit(&pool->stopping, 1, memory_order_release);
    post(pool);
    for (int k = 0; k < started; ++k) {
        pthread_join(pool->threads[k], NULL);
    }
}

static void release(worker_pool *pool)
{
    pthread_cond_destroy(&pool->idle);
    pthread_cond_destroy(&pool->job_posted);
    pthread_mutex_destroy(&pool->lock);
    free(pool->threads);
    free(pool->starts);
    free(pool);
}

/* Starts the workers, counting them in pool->started; 0, or pthread_create's error. */
static int start_workers(void *context)
{
    worker_pool *pool = context;
    for (pool->started = 0; pool->started < pool->n_workers; ++pool->started) {
        int k = pool->started;
        pool->starts[k] = (worker_start){pool, k + 1};
        int status = pthread_create(&pool->threads[k], NULL, worker_main, &pool->starts[k]);
        if (status != 0) {
            return status;
        }
    }
    return 0;
}

worker_pool *worker_pool_new(int n_workers, int *error)
{
    worker_pool *pool = calloc(1, sizeof *pool);
    if (pool == NULL) {
        *error = ENOMEM;
        return NULL;
    }
    pool->threads = calloc((size_t)n_workers, sizeof *pool->threads);
    pool->starts = calloc((size_t)n_workers, sizeof *pool->starts);
    pthread_mutex_init(&pool->lock, NULL);
    pthread_cond_init(&pool->job_posted, NULL);
    pthread_cond_init(&pool->idle, NULL);
    atomic_init(&pool->generation, 0);
    atomic_init(&pool->claim, 0); /* no task: a worker that wakes takes none */
    atomic_init(&pool->busy, 0);
    atomic_init(&pool->stopping, 0);
    pool->n_workers = n_workers;
    pool->owner = current_process_id();
    if (pool->threads == NULL || pool->starts == NULL) {
        *error = ENOMEM;
        release(pool);
        return NULL;
    }
    /* the workers inherit the mask: Ctrl-C and timers keep reaching the application's
     * threads, while a fault in an FMU still reaches the handlers installed for it */
    int status = with_asynchronous_signals_blocked(start_workers, pool);
    if (status != 0) {
        stop_workers(pool, pool->started);
        release(pool);
        *error = status;
        return NULL;
    }
    return pool;
}

void worker_pool_free(worker_pool *pool)
{
    if (pool == NULL) {
        return;
    }
    /* a forked copy has no threads to join */
    stop_workers(pool, pool->owner == current_process_id() ? pool->n_workers : 0);
    release(pool);
}

int worker_pool_threads(const worker_pool *pool)
{
    return pool->n_workers + 1;
}

void worker_pool_run(worker_pool *pool, worker_task task, void *context, int n_tasks)
{
    if (n_tasks <= 0) {
        return;
    }
    if (pool->owner != current_process_id()) {
        for (int k = 0; k < n_tasks; ++k) {
            task(context, k, 0);
        }
        return;
    }
    pool->task = task;
    pool->context = context;
    atomic_store(&pool->claim, (uint_least64_t)n_tasks << 32 | 1);
    post(pool);
    task(context, 0, 0);
    take_tasks(pool, 0);
    for (int poll = 0; poll < SPIN_POLLS && atomic_load(&pool->busy) > 0; ++poll) {
    }
    if (atomic_load(&pool->busy) > 0) {
        pthread_mutex_lock(&pool->lock);
        while (atomic_load(&pool->busy) > 0) {
            pthread_cond_wait(&pool->idle, &pool->lock);
        }
        pthread_mutex_unlock(&pool->lock);
    }
}

int worker_pool_self(const worker_pool *pool)
{
    pthread_t self = pthread_self();
    for (int k = 0; k < pool->n_workers; ++k) {
        if (pthread_equal(self, pool->threads[k])) {
            return k + 1;
        }
    }
    return 0;
}
