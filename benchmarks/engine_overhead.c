/* The engine's cost per macro step against a bare C loop of fmi2DoStep, for pendulum_euler
 * FMUs, 10 000 steps. The ratio depends on how much work one doStep does, so two step sizes are
 * measured: 1e-4 s (one Euler substep per doStep: the lightest FMU work, so the engine's share
 * shows) and 1e-3 s (ten substeps). Measured side by side, best of five; prints ratios and the
 * engine's extra nanoseconds per FMU step against a loop of fmi2DoStep alone and against one
 * that also sets the input and reads the outputs like the engine.
 *
 * Usage: engine_overhead                      1 and 100 FMUs at both step sizes
 *        engine_overhead N_FMUS DT REPEATS    one case (e.g. under callgrind, REPEATS 1)
 * (built by meson next to the engine's C tests) */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "test_support.h"

enum { STEPS = 10000, DEFAULT_REPEATS = 5 };
/* pendulum_euler's default internal step: a doStep of dt runs dt / this Euler substeps */
static const double EULER_INTERNAL_STEP = 1e-4;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void start_all(ssx_fmu **fmus, int n)
{
    for (int i = 0; i < n; ++i) {
        CHECK(start_pendulum(fmus[i], 0.0, 0.5, 0.0, 0.0) == 0);
    }
}

/* with_io: also set the input and get the three outputs, as the engine does every step */
static double bare_loop(ssx_fmu **fmus, int n, double dt, int with_io)
{
    static const unsigned int input_vr[] = {PENDULUM_TORQUE};
    static const unsigned int output_vr[] = {PENDULUM_THETA, PENDULUM_OMEGA, PENDULUM_ALPHA};
    const double torque = 0.0;
    double outputs[3];
    start_all(fmus, n);
    double begin = now();
    for (long k = 0; k < STEPS; ++k) {
        double t = (double)k * dt;
        double h = (double)(k + 1) * dt - t;
        for (int i = 0; i < n; ++i) {
            if ((with_io && ssx_fmu_set_real(fmus[i], input_vr, 1, &torque) != 0) ||
                ssx_fmu_do_step(fmus[i], t, h, 1) != 0 ||
                (with_io && ssx_fmu_get_real(fmus[i], output_vr, 3, outputs) != 0)) {
                fprintf(stderr, "bare fmi2DoStep failed\n");
                exit(1);
            }
        }
    }
    return now() - begin;
}

static double engine_run(ssx_fmu **fmus, int n, double dt, size_t *history_bytes)
{
    start_all(fmus, n);
    ssx_system *sys = ssx_system_new("overhead");
    char name[32];
    for (int i = 0; i < n; ++i) {
        snprintf(name, sizeof name, "pendulum%d", i);
        add_pendulum(sys, name, fmus[i]);
    }
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    double begin = now();
    CHECK_OK(sys, ssx_run(sys, 0.0, STEPS * dt, dt));
    double elapsed = now() - begin;
    CHECK(ssx_history_length(sys) == STEPS + 1);
    *history_bytes = ssx_history_bytes(sys);
    ssx_system_free(sys);
    return elapsed;
}

static void measure(int n, double dt, int repeats)
{
    ssx_fmu **fmus = malloc((size_t)n * sizeof *fmus);
    CHECK(fmus != NULL);
    for (int i = 0; i < n; ++i) {
        fmus[i] = load_fmu("pendulum_euler");
    }
    double best_bare = INFINITY, best_io = INFINITY, best_engine = INFINITY;
    size_t bytes = 0;
    for (int r = 0; r < repeats; ++r) {
        best_bare = fmin(best_bare, bare_loop(fmus, n, dt, 0));
        best_io = fmin(best_io, bare_loop(fmus, n, dt, 1));
        best_engine = fmin(best_engine, engine_run(fmus, n, dt, &bytes));
    }
    double fmu_steps = (double)STEPS * n;
    /* raw size: 3 outputs per FMU plus the time axis, float64, per sample */
    double raw = (double)(STEPS + 1) * (3.0 * n + 1.0) * sizeof(double);
    printf("%3d FMU(s) x %d steps of %g s (%.0f Euler substeps per doStep): bare doStep %.2f ms, "
           "bare doStep+set+get %.2f ms, engine %.2f ms\n"
           "    engine / bare doStep %.2f (%.0f ns more per FMU step), engine / bare with set+get "
           "%.2f (%.0f ns more); history %.2f x raw float64\n",
           n, STEPS, dt, dt / EULER_INTERNAL_STEP, 1e3 * best_bare, 1e3 * best_io,
           1e3 * best_engine, best_engine / best_bare, 1e9 * (best_engine - best_bare) / fmu_steps,
           best_engine / best_io, 1e9 * (best_engine - best_io) / fmu_steps, (double)bytes / raw);
    for (int i = 0; i < n; ++i) {
        ssx_fmu_free(fmus[i]);
    }
    free(fmus);
}

int main(int argc, char **argv)
{
    if (argc == 4) {
        int n = atoi(argv[1]);
        double dt = atof(argv[2]);
        int repeats = atoi(argv[3]);
        CHECK(n > 0 && dt > 0.0 && repeats > 0);
        measure(n, dt, repeats);
        return 0;
    }
    CHECK(argc == 1);
    static const double step_sizes[] = {1e-4, 1e-3};
    for (int i = 0; i < 2; ++i) {
        measure(1, step_sizes[i], DEFAULT_REPEATS);
        measure(100, step_sizes[i], DEFAULT_REPEATS);
    }
    return 0;
}
