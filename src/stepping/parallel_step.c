/* Stepping a batch of components on the system's threads; see parallel_step.h. */
#define _POSIX_C_SOURCE 200809L

#include "parallel_step.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "component_calls.h"
#include "error.h"
#include "worker_pool.h"

/* Handing work to a thread costs a wake-up and moving its FMUs' data between cores: a few
 * microseconds on an idle machine, tens on a busy one. So each thread a batch is shared with
 * must get at least this much of its measured work: a batch of less steps on the calling
 * thread alone, a larger one on as many threads as it has such shares (benchmarks/
 * parallel_stepping.py: 100 gain FMUs step in about 10 us and do not gain from a second
 * thread). */
#define SHARED_WORK_MIN_S 20e-6
/* Slices per thread sharing a batch: each thread steps contiguous components (one claim per
 * slice, not per FMU), with a few slices each to even out FMUs of unequal cost. */
enum { SLICES_PER_THREAD = 2 };

/* What one thread left behind after its tasks of a batch. */
typedef struct {
    ssx_error error;       /* its first failure */
    ssx_error later_error; /* where its later failures go: only the first can be the batch's */
    ssx_termination termination;
    int failed_at;      /* the task of its first failure, -1: none */
    int failed_in_step; /* it failed in its doStep (counted), not while its inputs were set */
    int terminated_at;  /* the task whose request is in `termination`, -1: none */
} thread_report;

struct parallel_plan {
    worker_pool *pool;
    int threads;
    unsigned char *on_pool; /* per component: it may step on any thread */
    ssx_component **tasks;  /* the current batch's components that step on the pool */
    int *owner;             /* the thread that stepped each task */
    int n_tasks;
    int n_slices;           /* the batch's tasks in this many contiguous slices */
    thread_report *reports; /* one per thread, 0 the calling thread's */
    double task_seconds;    /* recent cost of one pool task (a moving average), < 0 unknown */
    double caller_seconds;  /* in the current batch, the calling thread's time in its tasks */
    int caller_tasks;
    ssx_system *sys; /* the current batch's system and step */
    double t;
    double h;
    parallel_batch *batches;
    int n_batches;
};

/* ------------------------------------------------------------------ the records */

/* While a batch runs: the records of the thread that calls (the system's thread_records). */
static ssx_error *thread_error(void *plan)
{
    parallel_plan *p = plan;
    thread_report *r = &p->reports[worker_pool_self(p->pool)];
    return r->failed_at < 0 ? &r->error : &r->later_error;
}

static ssx_termination *thread_termination(void *plan)
{
    parallel_plan *p = plan;
    return &p->reports[worker_pool_self(p->pool)].termination;
}

/* ------------------------------------------------------------------ the plan */

void parallel_free(parallel_plan *plan)
{
    if (plan == NULL) {
        return;
    }
    worker_pool_free(plan->pool);
    free(plan->on_pool);
    free(plan->tasks);
    free(plan->owner);
    free(plan->reports);
    free(plan->batches);
    free(plan);
}

int parallel_batches(const parallel_plan *plan, const parallel_batch **batches)
{
    *batches = plan->batches;
    return plan->n_batches;
}

typedef struct {
    uintptr_t instance;
    int component;
} fmu_user;

static int by_fmu(const void *a, const void *b)
{
    uintptr_t x = ((const fmu_user *)a)->instance;
    uintptr_t y = ((const fmu_user *)b)->instance;
    return (x > y) - (x < y);
}

/* FMU components the engine steps or integrates (Co-Simulation, Model Exchange) whose Python
 * does not step them, unless the FMU must stay on one thread
 * (canBeInstantiatedOnlyOncePerProcess: its binary keeps globals) or another component uses
 * the same FMU instance (the two would step it at once). */
static int choose_pool_components(parallel_plan *p, const ssx_system *sys)
{
    int n = sys->n_components;
    fmu_user *users = malloc(((size_t)n + 1) * sizeof *users);
    if (users == NULL) {
        return -1;
    }
    int n_users = 0;
    for (int i = 0; i < n; ++i) {
        const ssx_component *c = sys->components[i];
        const void *shared = c->ops->shared_with_threads != NULL ? c->ops->shared_with_threads(c)
                                                                 : NULL;
        p->on_pool[i] = shared != NULL && c->hooks.do_step == NULL && !c->calling_thread_only;
        if (shared != NULL) {
            users[n_users++] = (fmu_user){(uintptr_t)shared, i};
        }
    }
    qsort(users, (size_t)n_users, sizeof *users, by_fmu);
    for (int k = 1; k < n_users; ++k) {
        if (users[k].instance == users[k - 1].instance) {
            p->on_pool[users[k].component] = 0;
            p->on_pool[users[k - 1].component] = 0;
        }
    }
    free(users);
    return 0;
}

/* Gauss-Seidel steps each component from the outputs its drivers have just before it steps.
 * Consecutive components none of which drives a later one of them see the same values when
 * their inputs are all set first: they form a batch. A loop group's members step from the
 * loop's solution, and are a batch of their own. */
static int build_batches(parallel_plan *p, const ssx_system *sys)
{
    int *batch_of = malloc(((size_t)sys->n_components + 1) * sizeof *batch_of);
    if (batch_of == NULL) {
        return -1;
    }
    for (int i = 0; i < sys->n_components; ++i) {
        batch_of[i] = -1;
    }
    p->n_batches = 0;
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        const ssx_group *g = &sys->groups[gi];
        if (g->is_loop) {
            p->batches[p->n_batches++] = (parallel_batch){g->first, g->size, gi};
            continue;
        }
        for (int m = 0; m < g->size; ++m) {
            const ssx_component *c = sys->components[sys->order[g->first + m]];
            int last = p->n_batches - 1;
            int joins = last >= 0 && p->batches[last].group < 0;
            for (int i = 0; i < c->n_inputs && joins; ++i) {
                int driver = c->input_driver[i];
                joins = driver < 0 || batch_of[sys->connections[driver].src_component] != last;
            }
            if (!joins) {
                p->batches[++last] = (parallel_batch){g->first + m, 0, -1};
                p->n_batches++;
            }
            p->batches[last].size++;
            batch_of[c->index] = last;
        }
    }
    free(batch_of);
    return 0;
}

int parallel_prepare(ssx_system *sys)
{
    parallel_plan *old = sys->parallel;
    sys->parallel = NULL;
    worker_pool *pool = NULL;
    if (old != NULL && sys->threads > 1 && worker_pool_threads(old->pool) == sys->threads) {
        pool = old->pool; /* the same threads serve the new plan */
        old->pool = NULL;
    }
    parallel_free(old);
    if (sys->threads <= 1) {
        return 0;
    }
    size_t n = (size_t)sys->n_components + 1;
    parallel_plan *p = calloc(1, sizeof *p);
    if (p != NULL) {
        p->threads = sys->threads;
        p->on_pool = calloc(n, sizeof *p->on_pool);
        p->tasks = calloc(n, sizeof *p->tasks);
        p->owner = calloc(n, sizeof *p->owner);
        p->reports = calloc((size_t)sys->threads, sizeof *p->reports);
        p->batches = calloc(n, sizeof *p->batches);
        p->task_seconds = -1.0;
    }
    if (p == NULL || p->on_pool == NULL || p->tasks == NULL || p->owner == NULL ||
        p->reports == NULL || p->batches == NULL || choose_pool_components(p, sys) != 0 ||
        build_batches(p, sys) != 0) {
        worker_pool_free(pool);
        parallel_free(p);
        return fail(sys, -1, -1, sys->time, "system '%s': out of memory planning %d threads",
                    sys->name, sys->threads);
    }
    if (pool == NULL) {
        int error = 0;
        pool = worker_pool_new(sys->threads - 1, &error);
        if (pool == NULL) {
            parallel_free(p);
            return fail(sys, -1, -1, sys->time, "system '%s': cannot start %d worker threads: %s",
                        sys->name, sys->threads - 1, strerror(error));
        }
    }
    p->pool = pool;
    sys->parallel = p;
    return 0;
}

/* ------------------------------------------------------------------ stepping a batch */

/* A thread goes on after a failure: the tasks after it are not needed, but the tasks before
 * it may be waiting for a thread, and one that stops would not save time. */
/* A sample counts for at most this many times the average: on a shared machine the process is
 * preempted for milliseconds now and then, and one preempted batch of a few microseconds would
 * otherwise have the next tens of batches shared (the 2-core figures of docs/performance/
 * threads.md: 0.68x on two threads at 31 us per step before). A lasting rise still gets through,
 * by a quarter per batch. */
#define TASK_COST_SAMPLE_MAX 2.0

/* One batch's cost per task into the moving average that decides whether the next is shared. */
static void note_task_cost(parallel_plan *p, double seconds_per_task)
{
    if (p->task_seconds < 0.0) {
        p->task_seconds = seconds_per_task;
        return;
    }
    double ceiling = TASK_COST_SAMPLE_MAX * p->task_seconds;
    double sample = seconds_per_task < ceiling ? seconds_per_task : ceiling;
    p->task_seconds = 0.75 * p->task_seconds + 0.25 * sample;
}

static void step_one(void *context, int k, int thread);

/* One slice of the batch's tasks, contiguous. The calling thread times its own slices: what
 * one task costs, without the waiting. */
static void step_slice(void *context, int slice, int thread)
{
    parallel_plan *p = context;
    int first = (int)((long)slice * p->n_tasks / p->n_slices);
    int end = (int)((long)(slice + 1) * p->n_tasks / p->n_slices);
    double start = thread == 0 ? monotonic_seconds() : 0.0;
    for (int k = first; k < end; ++k) {
        step_one(context, k, thread);
    }
    if (thread == 0) {
        p->caller_seconds += monotonic_seconds() - start;
        p->caller_tasks += end - first;
    }
}

/* How many threads the batch pays off on: one per SHARED_WORK_MIN_S of its measured work, at
 * least one, at most the system's (unknown cost: all, to measure it). */
static int threads_paying_off(const parallel_plan *p)
{
    if (p->task_seconds < 0.0) {
        return p->threads;
    }
    double shares = p->task_seconds * p->n_tasks / SHARED_WORK_MIN_S;
    return shares >= p->threads ? p->threads : shares < 1.0 ? 1 : (int)shares;
}

static void step_one(void *context, int k, int thread)
{
    parallel_plan *p = context;
    thread_report *r = &p->reports[thread];
    ssx_component *c = p->tasks[k];
    p->owner[k] = thread;
    int first_failure = r->failed_at < 0;
    if (component_write_inputs(p->sys, c) != 0) {
        r->failed_at = first_failure ? k : r->failed_at;
        return;
    }
    /* the built-in step: a pool component has no Python hook, and the calling thread counts
     * the step when it replays the batch */
    int status = c->ops->do_step(p->sys, c, p->t, p->h);
    if (r->terminated_at < 0 && r->termination.component >= 0) {
        r->terminated_at = k;
    }
    if (status != 0 && first_failure) {
        r->failed_at = k;
        r->failed_in_step = 1;
    }
}

/* What one thread would have done, in member order: steps the members that stay on the
 * calling thread, counts the pool's steps, and takes over the first termination request and
 * the first failure. */
static int replay(ssx_system *sys, const int *members, int n, double t, double h,
                  member_step step_member)
{
    parallel_plan *p = sys->parallel;
    int task = 0;
    for (int m = 0; m < n; ++m) {
        ssx_component *c = sys->components[members[m]];
        if (!p->on_pool[c->index]) {
            if (step_member(sys, c, t, h) != 0) {
                return -1;
            }
            continue;
        }
        const thread_report *r = &p->reports[p->owner[task]];
        int failed = r->failed_at == task;
        if (!failed || r->failed_in_step) {
            sys->stats.do_step_calls++;
        }
        if (r->terminated_at == task && sys->termination.component < 0) {
            sys->termination = r->termination;
        }
        if (failed) {
            sys->error = r->error;
            return -1;
        }
        ++task;
    }
    return 0;
}

int parallel_step(ssx_system *sys, const int *members, int n, double t, double h,
                  member_step step_member)
{
    parallel_plan *p = sys->parallel;
    if (p != NULL) {
        p->n_tasks = 0;
        for (int m = 0; m < n; ++m) {
            if (p->on_pool[members[m]]) {
                p->tasks[p->n_tasks++] = sys->components[members[m]];
            }
        }
    }
    int sharing = 1;
    if (p != NULL && p->n_tasks >= 2) {
        sharing = threads_paying_off(p);
        sharing = sharing < p->n_tasks ? sharing : p->n_tasks;
    }
    if (sharing < 2) {
        int timed = p != NULL && p->n_tasks >= 2; /* a batch that might be shared next time */
        double start = timed ? monotonic_seconds() : 0.0;
        for (int m = 0; m < n; ++m) {
            if (step_member(sys, sys->components[members[m]], t, h) != 0) {
                return -1;
            }
        }
        if (timed) {
            note_task_cost(p, (monotonic_seconds() - start) / n);
        }
        return 0;
    }
    for (int thread = 0; thread < p->threads; ++thread) {
        thread_report *r = &p->reports[thread];
        r->failed_at = -1;
        r->failed_in_step = 0;
        r->terminated_at = -1;
        r->termination.component = -1;
    }
    p->sys = sys;
    p->t = t;
    p->h = h;
    p->caller_seconds = 0.0;
    p->caller_tasks = 0;
    sys->thread_records = (thread_records){thread_error, thread_termination, p};
    p->n_slices = sharing * SLICES_PER_THREAD < p->n_tasks ? sharing * SLICES_PER_THREAD
                                                            : p->n_tasks;
    worker_pool_run(p->pool, step_slice, p, p->n_slices);
    sys->thread_records = (thread_records){0};
    note_task_cost(p, p->caller_seconds / p->caller_tasks);
    return replay(sys, members, n, t, h, step_member);
}
