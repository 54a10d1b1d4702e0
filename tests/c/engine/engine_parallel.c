/* Stepping on several threads (ssx_set_threads): the same histories, statistics, errors and
 * terminations as one thread, and the components that must stay on the calling thread stay
 * there. */
#define _GNU_SOURCE
#include <math.h>
#include <string.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_support.h"

enum { PENDULUMS = 6, GAIN_Y = 0, GAIN_U = 1, GAIN_K = 2, SUM_Y = 0, SUM_U = 1, SUM_B = 2,
       FAILING_Y = 0, FAILING_FAIL_TIME = 2, TERMINATING_Y = 0, TERMINATING_STOP_TIME = 3,
       PROBE_THREAD = 0, PROBE_PARTNERS = 1 };

/* Everything a run leaves that one thread and several must agree on. */
typedef struct {
    size_t length;
    double *time;
    double *values[PENDULUMS + 2];
    int n_outputs[PENDULUMS + 2];
    int n_components;
    ssx_statistics stats;
    size_t events;
    ssx_error error;
    ssx_termination termination;
    int status;
} outcome;

/* n_outputs: each component's outputs, or NULL for three each (pendulums). */
static void keep(outcome *o, ssx_system *sys, int n_components, const int *n_outputs,
                 int status)
{
    o->status = status;
    o->length = ssx_history_length(sys);
    o->n_components = n_components;
    o->time = malloc(o->length * sizeof(double));
    memcpy(o->time, ssx_history_time(sys), o->length * sizeof(double));
    for (int c = 0; c < n_components; ++c) {
        o->n_outputs[c] = n_outputs != NULL ? n_outputs[c] : 3;
        size_t bytes = o->length * (size_t)o->n_outputs[c] * sizeof(double);
        o->values[c] = malloc(bytes);
        memcpy(o->values[c], ssx_history_values(sys, c), bytes);
    }
    ssx_get_statistics(sys, &o->stats);
    o->events = ssx_event_count(sys);
    o->error = *ssx_last_error(sys);
    o->termination = *ssx_get_termination(sys);
}

static void release(outcome *o)
{
    free(o->time);
    for (int c = 0; c < o->n_components; ++c) {
        free(o->values[c]);
    }
}

#define CHECK_MESSAGE_TEXT(message, text) CHECK(strstr((message), (text)) != NULL)

/* Bit for bit: memcmp, not a tolerance. */
static void check_same(const outcome *a, const outcome *b)
{
    CHECK(a->status == b->status);
    CHECK(a->length == b->length && a->length >= 1);
    CHECK(memcmp(a->time, b->time, a->length * sizeof(double)) == 0);
    for (int c = 0; c < a->n_components; ++c) {
        size_t bytes = a->length * (size_t)a->n_outputs[c] * sizeof(double);
        CHECK(memcmp(a->values[c], b->values[c], bytes) == 0);
    }
    CHECK(memcmp(&a->stats, &b->stats, sizeof a->stats) == 0);
    CHECK(a->events == b->events);
    CHECK(a->error.kind == b->error.kind && a->error.component == b->error.component);
    CHECK(a->error.fmi_status == b->error.fmi_status);
    CHECK((isnan(a->error.time) && isnan(b->error.time)) || a->error.time == b->error.time);
    CHECK(strcmp(a->error.message, b->error.message) == 0);
    CHECK(a->termination.component == b->termination.component);
    CHECK(strcmp(a->termination.message, b->termination.message) == 0);
}

/* The wall: the pendulum starts again where it hit, with its velocity reversed. */
static int bounce(void *user, const int *indicators, int n, double t)
{
    wall_bounce *b = user;
    if (n != 1 || indicators[0] != b->component) {
        return -1;
    }
    const double *out = ssx_outputs(b->sys, b->component);
    b->calls++;
    return start_pendulum(b->fmu, t, out[0], -out[1], 1e-8) == 0 ? 0 : -1;
}

/* Six CVODE pendulums, pendulum i's angle driving pendulum i + 2's torque: Gauss-Seidel steps
 * them as the batches {0, 1}, {2, 3}, {4, 5}. With `hybrid`, each bounces off a wall at
 * theta = 0 (its indicator i, handled by itself). */
static void pendulums(int threads, ssx_coupling coupling, int hybrid, outcome *o)
{
    ssx_fmu *fmus[PENDULUMS];
    wall_bounce walls[PENDULUMS];
    ssx_system *sys = ssx_system_new("pendulums");
    for (int i = 0; i < PENDULUMS; ++i) {
        char name[8];
        snprintf(name, sizeof name, "P%d", i);
        fmus[i] = load_fmu("pendulum_cvode");
        CHECK(start_pendulum(fmus[i], 0.0, 0.2 + 0.07 * i, 0.0, 1e-8) == 0);
        int c = add_pendulum(sys, name, fmus[i]);
        if (hybrid) {
            walls[i] = (wall_bounce){.sys = sys, .fmu = fmus[i], .component = c};
            const ssx_hooks hooks = {.user = &walls[i], .handle_events = bounce};
            CHECK_OK(sys, ssx_set_hooks(sys, c, &hooks));
            CHECK(ssx_add_indicator_output(sys, c, 0, -1) == c);
            CHECK_OK(sys, ssx_add_event_connection(sys, c, c));
        }
    }
    for (int i = 0; i + 2 < PENDULUMS; ++i) {
        CHECK_OK(sys, ssx_connect(sys, i, 0, i + 2, 0, 3.0, 0.0));
    }
    CHECK_OK(sys, ssx_set_coupling(sys, coupling));
    CHECK_OK(sys, ssx_set_threads(sys, threads));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    keep(o, sys, PENDULUMS, NULL, ssx_run(sys, 0.0, 1.5, 0.01));
    ssx_system_free(sys);
    for (int i = 0; i < PENDULUMS; ++i) {
        ssx_fmu_free(fmus[i]);
    }
}

static void same_histories(void)
{
    for (int coupling = SSX_GAUSS_SEIDEL; coupling <= SSX_JACOBI; ++coupling) {
        outcome one, two, four;
        pendulums(1, (ssx_coupling)coupling, 0, &one);
        pendulums(2, (ssx_coupling)coupling, 0, &two);
        pendulums(4, (ssx_coupling)coupling, 0, &four);
        CHECK(one.status == 0);
        CHECK(one.stats.do_step_calls == 150 * PENDULUMS);
        check_same(&one, &two);
        check_same(&one, &four);
        release(&one);
        release(&two);
        release(&four);
    }
}

static void same_events(void)
{
    for (int coupling = SSX_GAUSS_SEIDEL; coupling <= SSX_JACOBI; ++coupling) {
        outcome one, two;
        pendulums(1, (ssx_coupling)coupling, 1, &one);
        pendulums(2, (ssx_coupling)coupling, 1, &two);
        CHECK(one.status == 0);
        CHECK(one.events >= PENDULUMS);
        CHECK(one.stats.state_restores > 0);
        check_same(&one, &two);
        release(&one);
        release(&two);
    }
}

static ssx_fmu *started(const char *stem, unsigned int vr, double value)
{
    ssx_fmu *fmu = load_fmu(stem);
    CHECK(start_fmu(fmu, 0.0, 0.0, &vr, &value, 1) <= 1);
    return fmu;
}

static int add_block(ssx_system *sys, const char *name, ssx_fmu *fmu, int y, int u)
{
    int c = ssx_add_fmu_component(sys, name, fmu, 1);
    CHECK(ssx_add_output(sys, c, SSX_REAL, (unsigned)y) == 0);
    if (u >= 0) {
        CHECK(ssx_add_input(sys, c, SSX_REAL, (unsigned)u, 0.0) == 0);
    }
    return c;
}

/* Gauss-Seidel with an algebraic loop: the loop's members (a sum and a gain, y = 1 - 0.5 y)
 * are a batch of their own, solved after they step; the pendulum after the loop is driven by
 * it. */
static void loop_system(int threads, outcome *o)
{
    ssx_fmu *first = load_fmu("pendulum_cvode");
    ssx_fmu *last = load_fmu("pendulum_cvode");
    CHECK(start_pendulum(first, 0.0, 0.3, 0.0, 1e-8) == 0);
    CHECK(start_pendulum(last, 0.0, 0.4, 0.0, 1e-8) == 0);
    ssx_fmu *sum = started("sum", SUM_B, 1.0);
    ssx_fmu *gain = started("gain", GAIN_K, 0.5);
    ssx_system *sys = ssx_system_new("loop");
    int p0 = add_pendulum(sys, "P0", first);
    int s = add_block(sys, "S", sum, SUM_Y, SUM_U);
    int g = add_block(sys, "G", gain, GAIN_Y, GAIN_U);
    int p1 = add_pendulum(sys, "P1", last);
    CHECK_OK(sys, ssx_connect(sys, s, 0, g, 0, 1.0, 0.0));
    CHECK_OK(sys, ssx_connect(sys, g, 0, s, 0, 1.0, 0.0));
    CHECK_OK(sys, ssx_connect(sys, g, 0, p1, 0, 1.0, 0.0));
    const int order[] = {p0, s, g, p1};
    const int sizes[] = {1, 2, 1};
    const int loops[] = {0, 1, 0};
    CHECK_OK(sys, ssx_set_schedule(sys, order, sizes, loops, 3));
    CHECK_OK(sys, ssx_set_threads(sys, threads));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    const int n_outputs[] = {3, 1, 1, 3};
    keep(o, sys, 4, n_outputs, ssx_run(sys, 0.0, 1.0, 0.01));
    CHECK_CLOSE(ssx_outputs(sys, s)[0], 2.0 / 3.0, 1e-9);
    ssx_system_free(sys);
    ssx_fmu_free(first);
    ssx_fmu_free(last);
    ssx_fmu_free(sum);
    ssx_fmu_free(gain);
}

static void same_loop_solutions(void)
{
    outcome one, two;
    loop_system(1, &one);
    loop_system(2, &two);
    CHECK(one.status == 0 && one.stats.loop_solves > 0);
    check_same(&one, &two);
    release(&one);
    release(&two);
}

/* A thread probe that steps only when `partners` probes step at once (0: no wait). */
static ssx_fmu *started_probe(int partners)
{
    ssx_fmu *fmu = load_fmu("thread_probe");
    const unsigned int vr = PROBE_PARTNERS;
    const ssx_fmu_experiment experiment = {.start_time = 0.0};
    const ssx_fmu_values starts = {.integer_vr = &vr, .integer_values = &partners, .n_integer = 1};
    CHECK(ssx_fmu_initialize(fmu, &experiment, &starts, NULL, NULL) == 0);
    return fmu;
}

static int add_probe(ssx_system *sys, const char *name, ssx_fmu **fmu, int partners)
{
    *fmu = started_probe(partners);
    return add_block(sys, name, *fmu, PROBE_THREAD, -1);
}

/* The calling thread takes the first pool task, R1, and waits in its step for a partner; so
 * the worker must take F and then R2, R1's partner: F fails on the worker, in the step to 0.4.
 * C4, a failing FMU kept on the calling thread, fails in the same step but comes later in
 * schedule order: F is reported, as on one thread, and C4 is not stepped. One thread steps
 * the same system without the partners' wait. */
static void failure_system(int threads, outcome *o, long *late_steps)
{
    ssx_fmu *fmus[5];
    ssx_system *sys = ssx_system_new("failures");
    int partners = threads > 1 ? 2 : 0;
    add_probe(sys, "R1", &fmus[0], partners);
    fmus[1] = started("failing", FAILING_FAIL_TIME, 0.35);
    add_block(sys, "F", fmus[1], FAILING_Y, -1);
    add_probe(sys, "R2", &fmus[2], partners);
    fmus[3] = load_fmu("pendulum_euler");
    CHECK(start_pendulum(fmus[3], 0.0, 0.3, 0.0, 0.0) == 0);
    add_pendulum(sys, "P", fmus[3]);
    fmus[4] = started("failing", FAILING_FAIL_TIME, 0.35);
    add_block(sys, "C4", fmus[4], FAILING_Y, -1);
    CHECK_OK(sys, ssx_set_calling_thread_only(sys, 4, 1));
    CHECK_OK(sys, ssx_set_coupling(sys, SSX_JACOBI));
    CHECK_OK(sys, ssx_set_threads(sys, threads));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    const int n_outputs[] = {0, 1, 0, 3, 1}; /* the probes' thread ids differ */
    keep(o, sys, 5, n_outputs, ssx_run(sys, 0.0, 1.0, 0.1));
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(fmus[4], &counters);
    *late_steps = counters.do_step;
    ssx_system_free(sys);
    for (int i = 0; i < 5; ++i) {
        ssx_fmu_free(fmus[i]);
    }
}

static void first_failure_in_order(void)
{
    outcome one, two;
    long late_one, late_two;
    failure_system(1, &one, &late_one);
    failure_system(2, &two, &late_two);
    CHECK(one.status == -1);
    CHECK(one.error.component == 1 && one.error.kind == SSX_ERROR_FMI);
    CHECK(one.error.time == 0.30000000000000004);
    CHECK_MESSAGE_TEXT(one.error.message, "component 'F': fmi2DoStep failed at "
                                          "t=0.30000000000000004 with status fmi2Error (FMU "
                                          "log: fmi2DoStep from t = ");
    CHECK_MESSAGE_TEXT(one.error.message, "a deliberate failure");
    check_same(&one, &two);
    CHECK(late_one == 3 && late_two == 3); /* C4 stepped to 0.3, never into the failing step */
    release(&one);
    release(&two);
}

/* As above, the worker steps T, a ramp that asks to stop at 0.45: the run ends at 0.4. */
static void termination_system(int threads, outcome *o)
{
    ssx_fmu *fmus[4];
    ssx_system *sys = ssx_system_new("termination");
    int partners = threads > 1 ? 2 : 0;
    add_probe(sys, "R1", &fmus[0], partners);
    fmus[1] = started("terminating", TERMINATING_STOP_TIME, 0.45);
    add_block(sys, "T", fmus[1], TERMINATING_Y, -1);
    add_probe(sys, "R2", &fmus[2], partners);
    fmus[3] = load_fmu("pendulum_euler");
    CHECK(start_pendulum(fmus[3], 0.0, 0.3, 0.0, 0.0) == 0);
    add_pendulum(sys, "P", fmus[3]);
    CHECK_OK(sys, ssx_set_coupling(sys, SSX_JACOBI));
    CHECK_OK(sys, ssx_set_threads(sys, threads));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    const int n_outputs[] = {0, 1, 0, 3};
    keep(o, sys, 4, n_outputs, ssx_run(sys, 0.0, 1.0, 0.1));
    CHECK(ssx_time(sys) == 0.4);
    ssx_system_free(sys);
    for (int i = 0; i < 4; ++i) {
        ssx_fmu_free(fmus[i]);
    }
}

static void termination_on_a_worker(void)
{
    outcome one, two;
    termination_system(1, &one);
    termination_system(2, &two);
    CHECK(one.status == 0 && one.termination.component == 1);
    check_same(&one, &two);
    release(&one);
    release(&two);
}

/* A component of Python's kind (hooks), here in C: it notes the thread that stepped it. */
typedef struct {
    ssx_system *sys;
    int component;
    pid_t stepped_on;
} hooked_probe;

/* the system call, not glibc's gettid(), which the wheel's glibc 2.17 lacks (2.30) */
static pid_t thread_id(void)
{
    return (pid_t)syscall(SYS_gettid);
}

static int probe_step(void *user, double t, double dt)
{
    (void)t;
    (void)dt;
    hooked_probe *p = user;
    p->stepped_on = thread_id();
    ssx_outputs(p->sys, p->component)[0] = (double)p->stepped_on;
    return 0;
}

static int probe_outputs(void *user, double t)
{
    (void)t;
    hooked_probe *p = user;
    ssx_outputs(p->sys, p->component)[0] = (double)thread_id();
    return 0;
}

/* thread_probe FMUs report the thread that stepped them. A and B step only together, so the
 * calling thread (which takes A, the first pool task) and the worker (B) step at once; the
 * FMU marked calling-thread-only and the hooked component step on the calling thread. */
static void calling_thread_stays(void)
{
    ssx_fmu *fmus[3];
    ssx_system *sys = ssx_system_new("probes");
    add_probe(sys, "A", &fmus[0], 2);
    add_probe(sys, "B", &fmus[1], 2);
    int once = add_probe(sys, "Once", &fmus[2], 0);
    hooked_probe hooked = {.sys = sys};
    hooked.component = ssx_add_python_component(sys, "Hooked", 0);
    CHECK(ssx_add_output(sys, hooked.component, SSX_REAL, 0) == 0);
    const ssx_hooks hooks = {.user = &hooked, .do_step = probe_step,
                             .evaluate_outputs = probe_outputs};
    CHECK_OK(sys, ssx_set_hooks(sys, hooked.component, &hooks));
    CHECK_OK(sys, ssx_set_calling_thread_only(sys, once, 1));
    CHECK_OK(sys, ssx_set_coupling(sys, SSX_JACOBI));
    CHECK_OK(sys, ssx_set_threads(sys, 2));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.5, 0.1));
    const double caller = (double)thread_id();
    const size_t last = ssx_history_length(sys) - 1;
    CHECK(last == 5);
    for (size_t k = 1; k <= last; ++k) {
        CHECK(ssx_history_values(sys, 0)[k] == caller);
        CHECK(ssx_history_values(sys, 1)[k] != caller);
        CHECK(ssx_history_values(sys, once)[k] == caller);
        CHECK(ssx_history_values(sys, hooked.component)[k] == caller);
    }
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(stats.do_step_calls == 5 * 4);
    ssx_system_free(sys);
    for (int i = 0; i < 3; ++i) {
        ssx_fmu_free(fmus[i]);
    }
}

/* Two components on one FMU instance step it twice per step, which the FMU refuses; on the
 * pool they would also step it at once. Both stay on the calling thread: the same error. */
static void shared_instance(int threads, outcome *o)
{
    ssx_fmu *fmus[3];
    ssx_system *sys = ssx_system_new("twins");
    for (int i = 0; i < 3; ++i) {
        fmus[i] = started_probe(0);
    }
    const char *names[] = {"A", "Twin1", "Twin2", "B"};
    ssx_fmu *chosen[] = {fmus[0], fmus[1], fmus[1], fmus[2]};
    for (int i = 0; i < 4; ++i) {
        add_block(sys, names[i], chosen[i], 0, -1);
    }
    CHECK_OK(sys, ssx_set_coupling(sys, SSX_JACOBI));
    CHECK_OK(sys, ssx_set_threads(sys, threads));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    const int n_outputs[] = {1, 1, 1, 1};
    int status = ssx_run(sys, 0.0, 0.5, 0.1);
    /* the thread ids differ from run to run; the error and the statistics must not */
    keep(o, sys, 0, n_outputs, status);
    ssx_system_free(sys);
    for (int i = 0; i < 3; ++i) {
        ssx_fmu_free(fmus[i]);
    }
}

static void one_instance_two_components(void)
{
    outcome one, two;
    shared_instance(1, &one);
    shared_instance(2, &two);
    CHECK(one.status == -1 && one.error.component == 2);
    CHECK_MESSAGE_TEXT(one.error.message, "differs from the FMU's time 0.10000000000000001");
    check_same(&one, &two);
    release(&one);
    release(&two);
}

static int stop_at_once(void *user, double t)
{
    (void)t;
    ++*(int *)user;
    return 1;
}

/* The monitor still runs between macro steps on the calling thread, and stops the run; the
 * pool survives initializing again with the same and other thread counts, and a forked
 * process (which has none of the pool's threads) steps its copy on its one thread. */
static void monitor_reinitialize_and_fork(void)
{
    ssx_fmu *fmus[4];
    ssx_system *sys = ssx_system_new("pool");
    for (int i = 0; i < 4; ++i) {
        char name[8];
        snprintf(name, sizeof name, "P%d", i);
        fmus[i] = load_fmu("pendulum_euler");
        CHECK(start_pendulum(fmus[i], 0.0, 0.1 * (i + 1), 0.0, 0.0) == 0);
        add_pendulum(sys, name, fmus[i]);
    }
    CHECK_OK(sys, ssx_set_coupling(sys, SSX_JACOBI));
    CHECK(ssx_set_threads(sys, 0) == -1);
    CHECK_MESSAGE(sys, "threads must be between 1 and 256, not 0");
    CHECK(ssx_set_threads(sys, SSX_MAX_THREADS + 1) == -1);
    CHECK_OK(sys, ssx_set_threads(sys, 2));
    int monitor_calls = 0;
    CHECK_OK(sys, ssx_set_monitor(sys, stop_at_once, &monitor_calls));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_run(sys, 0.0, 1e4, 1e-3) == -1);
    CHECK(monitor_calls == 1 && ssx_last_error(sys)->kind == SSX_ERROR_CALLBACK);
    CHECK_MESSAGE(sys, "stopped by its monitor");
    CHECK_OK(sys, ssx_set_monitor(sys, NULL, NULL));
    const int counts[] = {2, 3, 1, 2};
    for (int k = 0; k < 4; ++k) {
        CHECK_OK(sys, ssx_set_threads(sys, counts[k]));
        CHECK_OK(sys, ssx_initialize(sys, ssx_time(sys)));
        CHECK_OK(sys, ssx_run(sys, ssx_time(sys), ssx_time(sys) + 0.1, 0.01));
    }
    double before_fork = ssx_time(sys);
    size_t samples = ssx_history_length(sys);
    pid_t child = fork();
    CHECK(child >= 0);
    if (child == 0) {
        int status = ssx_run(sys, before_fork, before_fork + 0.1, 0.01);
        _exit(status == 0 && ssx_history_length(sys) == samples + 10 ? 0 : 1);
    }
    int status = 0;
    CHECK(waitpid(child, &status, 0) == child);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    ssx_system_free(sys);
    for (int i = 0; i < 4; ++i) {
        ssx_fmu_free(fmus[i]);
    }
}

int main(void)
{
    same_histories();
    same_events();
    same_loop_solutions();
    first_failure_in_order();
    termination_on_a_worker();
    calling_thread_stays();
    one_instance_two_components();
    monitor_reinitialize_and_fork();
    printf("parallel stepping: same results on 1, 2 and 4 threads\n");
    return 0;
}
