/* The floor of a chain of N FMUs without the engine: each instance's input set from the one
 * before it, its fmi2DoStep and its output read, straight through FMI 2.0 in a C loop
 * (benchmarks/chain_scaling.py --direct prints it beside the engine's figures). The instances are
 * made one after the other, so what this measures at large N is the FMU's own memory.
 * Usage: chain_direct <binary> <modelDescription.xml> <N> <steps> <input> <output>
 * Prints: CPU nanoseconds per FMU step. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "fmu_harness.h"

#define DT 1e-3

static double cpu_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc != 7 && argc != 8) {
        fprintf(stderr,
                "usage: %s <binary> <modelDescription.xml> <N> <steps> <input> <output> "
                "[spacing]\n",
                argv[0]);
        return 2;
    }
    test_fmu fmu;
    fmu_open(&fmu, argv[1], argv[2]);
    long n = strtol(argv[3], NULL, 10);
    long steps = strtol(argv[4], NULL, 10);
    CHECK(n > 0 && steps > 0);
    fmi2ValueReference input = fmu_vr(&fmu, argv[5]);
    fmi2ValueReference output = fmu_vr(&fmu, argv[6]);
    size_t spacing = argc == 8 ? (size_t)strtoul(argv[7], NULL, 10) : 0;
    fmi2Component *chain = malloc((size_t)n * sizeof *chain);
    void **gaps = calloc((size_t)n, sizeof *gaps);
    CHECK(chain != NULL && gaps != NULL);
    for (long i = 0; i < n; ++i) {
        chain[i] = fmu_start(&fmu, 0.0, 0.0, NULL, NULL, 0);
        gaps[i] = spacing > 0 ? malloc(spacing) : NULL;
    }
    double start = cpu_ns();
    for (long k = 0; k < steps; ++k) {
        double value = 1.0; /* the first one's input */
        for (long i = 0; i < n; ++i) {
            CHECK_OK(fmu.set_real(chain[i], &input, 1, &value));
            CHECK_OK(fmu.do_step(chain[i], (double)k * DT, DT, fmi2True));
            CHECK_OK(fmu.get_real(chain[i], &output, 1, &value));
        }
    }
    printf("%.1f\n", (cpu_ns() - start) / ((double)n * (double)steps));
    for (long i = 0; i < n; ++i) {
        fmu.free_instance(chain[i]);
    }
    for (long i = 0; i < n; ++i) {
        free(gaps[i]);
    }
    free(gaps);
    free(chain);
    fmu_close(&fmu);
    return 0;
}
