/* Bouncing ball with the bounce inside the FMU, against the closed form.
 * Usage: test_fmu_bouncing_ball <binary> <modelDescription.xml> euler|cvode */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmu_harness.h"

#define G 9.81
#define E 0.8
#define H0 1.0
#define BOUNCES 5
#define EULER_STEP 1e-4 /* the FMU's default euler_step_size */

static int is_positive(double value)
{
    return value > 0.0;
}

static int is_negative(double value)
{
    return value < 0.0;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s <binary> <modelDescription.xml> euler|cvode\n", argv[0]);
        return 2;
    }
    int cvode = strcmp(argv[3], "cvode") == 0;
    test_fmu fmu;
    fmu_open(&fmu, argv[1], argv[2]);
    fmi2Component c = fmu_start(&fmu, cvode ? 1e-10 : 0.0, 0.0, NULL, NULL, 0);

    /* t1 = sqrt(2 h0 / g), then flights of 2 e^k v1 / g with v1 = g t1 */
    double expected = sqrt(2.0 * H0 / G), v1 = G * expected;
    double t = 0.0;
    for (int k = 0; k < BOUNCES; ++k) {
        double bounce = fmu_find_time(&fmu, c, t, 1e-3, 5.0, "v", is_positive, 1e-12, &t);
        char label[64];
        snprintf(label, sizeof label, "bounce %d [s]", k + 1);
        /* Euler's height runs ahead of the exact one by g t h / 2 (t since the last bounce):
         * the first fall lands h / 2 late, every later flight h late plus 2 dv / g for a
         * rebound speed that is too high by dv <= k g h. Summed: bound (k + 1)^2 h. */
        double n = k + 1;
        CHECK_NEAR(label, bounce, expected, cvode ? 1e-8 : n * n * EULER_STEP);
        CHECK_NEAR("rebound speed [m/s]", fmu_get(&fmu, c, "v"), pow(E, k + 1) * v1,
                   cvode ? 1e-7 : n * G * EULER_STEP);
        expected += 2.0 * pow(E, k + 1) * v1 / G;
        fmu_find_time(&fmu, c, t, 1e-3, 5.0, "v", is_negative, 1e-6, &t);
    }
    /* All bounces happen before t1 (1 + 2e/(1-e)) = 4.06 s; then the ball rests. */
    double t_rest = 6.0;
    CHECK_OK(fmu.do_step(c, t, t_rest - t, fmi2False));
    CHECK_NEAR("height at rest [m]", fmu_get(&fmu, c, "h"), 0.0, 0.0);
    CHECK_NEAR("velocity at rest [m/s]", fmu_get(&fmu, c, "v"), 0.0, 0.0);
    fmu.free_instance(c);
    fmu_close(&fmu);
    return 0;
}
