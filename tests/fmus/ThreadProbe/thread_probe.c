/* ThreadProbe.mo: `thread` is the Linux thread id of the thread that last computed the
 * outputs (each fmi2DoStep does), so a master's tests can see which of its threads stepped
 * the FMU. With partners = n > 1, a step waits until n instances of this binary have started
 * a step at once (one meeting per n steps started), then lasts 1 ms more (a master that judges
 * whether to share steps by their cost finds these worth sharing); a master that steps them
 * one after the other gets the step refused after 10 s instead. The meeting counter is the binary's one
 * global: it is what the instances share on purpose. */
#define _GNU_SOURCE
#include <stdatomic.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include "model.h"

enum { VR_THREAD, VR_PARTNERS, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_DISCRETE_OUTPUT(VR_THREAD, "thread", NULL, "id of the thread that last stepped the FMU",
                         DEPENDS_NONE, DEPENDS_NONE),
    INTEGER_PARAMETER(VR_PARTNERS, "partners", 0,
                      "instances that must be stepping at once (0 or 1: no wait)"),
};

enum { MEETING_TIMEOUT_S = 10 };

static atomic_long steps_started; /* by every instance with partners > 1, since loading */

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    (void)x;
    /* the system call, not glibc's gettid(), which the wheel's glibc 2.17 lacks (2.30) */
    v[VR_THREAD] = (double)syscall(SYS_gettid);
}

/* Step k (counted over all instances) belongs to meeting k / n, which is complete once
 * n * (k / n + 1) steps have started. */
static const char *meet_partners(const double *v, double t_end, step_refusal_kind *kind)
{
    (void)t_end;
    (void)kind;
    long n = (long)v[VR_PARTNERS];
    if (n <= 1) {
        return NULL;
    }
    long complete = n * (atomic_fetch_add(&steps_started, 1) / n + 1);
    struct timespec start, now;
    clock_gettime(CLOCK_MONOTONIC, &start);
    while (atomic_load(&steps_started) < complete) {
        nanosleep(&(struct timespec){0, 20000}, NULL);
        clock_gettime(CLOCK_MONOTONIC, &now);
        if (now.tv_sec - start.tv_sec > MEETING_TIMEOUT_S) {
            return "no partner started a step at the same time within 10 s";
        }
    }
    nanosleep(&(struct timespec){0, 1000000}, NULL);
    return NULL;
}

const model_definition fmu_model = {
    .name = "ThreadProbe",
    .description = "Reports the thread that stepped it; may wait for partners (ThreadProbe.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
    .step_refusal = meet_partners,
};
