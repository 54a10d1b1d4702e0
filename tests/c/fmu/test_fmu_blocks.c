/* The stateless and small models used to build coupled systems, against their equations.
 * Usage: test_fmu_blocks <binary> <modelDescription.xml> <fmu stem> */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmu_harness.h"

static void check_torsion_spring(test_fmu *fmu)
{
    const char *names[] = {"k", "d"};
    const double values[] = {50.0, 2.0};
    fmi2Component c = fmu_start(fmu, 0.0, 0.0, names, values, 2);
    fmu_set(fmu, c, "theta1", 0.3);
    fmu_set(fmu, c, "theta2", -0.1);
    fmu_set(fmu, c, "omega1", 1.5);
    fmu_set(fmu, c, "omega2", 0.5);
    double tau1 = -50.0 * (0.3 - -0.1) - 2.0 * (1.5 - 0.5);
    CHECK_NEAR("tau1 [N.m]", fmu_get(fmu, c, "tau1"), tau1, 1e-14);
    CHECK_NEAR("tau2 [N.m]", fmu_get(fmu, c, "tau2"), -tau1, 1e-14);
    CHECK_OK(fmu->do_step(c, 0.0, 0.1, fmi2False));
    CHECK_NEAR("tau1 after a step (no state) [N.m]", fmu_get(fmu, c, "tau1"), tau1, 1e-14);
    fmu->free_instance(c);
}

static void check_gain(test_fmu *fmu)
{
    const char *names[] = {"k"};
    const double values[] = {-2.5};
    fmi2Component c = fmu_start(fmu, 0.0, 0.0, names, values, 1);
    fmu_set(fmu, c, "u", 4.0);
    CHECK_NEAR("y = k u", fmu_get(fmu, c, "y"), -10.0, 0.0);
    fmu->free_instance(c);
}

static void check_sum(test_fmu *fmu)
{
    const char *names[] = {"b", "c"};
    const double values[] = {3.0, 0.5};
    fmi2Component c = fmu_start(fmu, 0.0, 0.0, names, values, 2);
    fmu_set(fmu, c, "u", 4.0);
    CHECK_NEAR("y = b - c u", fmu_get(fmu, c, "y"), 1.0, 0.0);
    fmu->free_instance(c);
}

/* With a piecewise-constant error, the integral is exact: e1 t1 + e2 (t - t1). */
static void check_pi_controller(test_fmu *fmu)
{
    const char *names[] = {"kp", "ki", "integral0"};
    const double values[] = {2.0, 3.0, 0.1};
    fmi2Component c = fmu_start(fmu, 0.0, 0.0, names, values, 3);
    fmu_set(fmu, c, "setpoint", 1.0);
    fmu_set(fmu, c, "measurement", 0.25);
    CHECK_NEAR("u at t = 0", fmu_get(fmu, c, "u"), 2.0 * 0.75 + 3.0 * 0.1, 1e-15);
    for (int k = 0; k < 10; ++k)
        CHECK_OK(fmu->do_step(c, k * 0.05, 0.05, fmi2False));
    fmu_set(fmu, c, "measurement", 1.5);
    for (int k = 10; k < 20; ++k)
        CHECK_OK(fmu->do_step(c, k * 0.05, 0.05, fmi2False));
    double integral = 0.1 + 0.75 * 0.5 - 0.5 * 0.5;
    /* sums of 5000 Euler substeps: rounding only */
    CHECK_NEAR("u at t = 1", fmu_get(fmu, c, "u"), 2.0 * -0.5 + 3.0 * integral, 1e-12);
    fmu->free_instance(c);
}

static void check_failing(test_fmu *fmu)
{
    const char *names[] = {"fail_time"};
    const double values[] = {0.5};
    fmi2Component c = fmu_start(fmu, 0.0, 0.0, names, values, 1);
    for (int k = 0; k < 5; ++k)
        CHECK_OK(fmu->do_step(c, k * 0.1, 0.1, fmi2False));
    int before = fmu->log.count;
    CHECK(fmu->do_step(c, 0.5, 0.1, fmi2False) == fmi2Error);
    CHECK(fmu->log.count > before);
    CHECK(strstr(fmu->log.last_message, "fail_time") != NULL);
    printf("failing.fmu logged: %s\n", fmu->log.last_message);
    fmu->free_instance(c);
}

/* The ball without an internal bounce, bounced by a master the way the seed does it: a new
 * instance initialized at the bounce time with h0 = 0 and v0 = -e v. */
static void check_bouncing_ball_continuous(test_fmu *fmu, double tolerance)
{
    fmi2Component c = fmu_start(fmu, 1e-10, 0.0, NULL, NULL, 0);
    double t1 = sqrt(2.0 / 9.81);
    CHECK_OK(fmu->do_step(c, 0.0, t1, fmi2False));
    CHECK_NEAR("h at the first impact [m]", fmu_get(fmu, c, "h"), 0.0, tolerance);
    double v = fmu_get(fmu, c, "v");
    fmu->free_instance(c);
    const char *names[] = {"h0", "v0"};
    const double values[] = {0.0, -0.8 * v};
    c = fmu_start(fmu, 1e-10, t1, names, values, 2);
    double flight = 2.0 * 0.8 * 9.81 * t1 / 9.81;
    CHECK_OK(fmu->do_step(c, t1, 0.5 * flight, fmi2False));
    CHECK_NEAR("v at the apex [m/s]", fmu_get(fmu, c, "v"), 0.0, 1e-9);
    CHECK_OK(fmu->do_step(c, t1 + 0.5 * flight, 0.5 * flight, fmi2False));
    CHECK_NEAR("h at the second impact [m]", fmu_get(fmu, c, "h"), 0.0, tolerance);
    fmu->free_instance(c);
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s <binary> <modelDescription.xml> <fmu stem>\n", argv[0]);
        return 2;
    }
    test_fmu fmu;
    fmu_open(&fmu, argv[1], argv[2]);
    const char *stem = argv[3];
    if (strcmp(stem, "torsion_spring") == 0)
        check_torsion_spring(&fmu);
    else if (strcmp(stem, "gain") == 0)
        check_gain(&fmu);
    else if (strcmp(stem, "sum") == 0)
        check_sum(&fmu);
    else if (strcmp(stem, "pi_controller") == 0)
        check_pi_controller(&fmu);
    else if (strcmp(stem, "failing") == 0)
        check_failing(&fmu);
    /* CVODE at rtol 1e-10; Euler's height runs ahead by g t h / 2, up to 3.5e-4 m here */
    else if (strcmp(stem, "bouncing_ball_continuous_cvode") == 0)
        check_bouncing_ball_continuous(&fmu, 1e-9);
    else if (strcmp(stem, "bouncing_ball_continuous_euler") == 0)
        check_bouncing_ball_continuous(&fmu, 5e-4);
    else
        CHECK(!"no check for this FMU");
    fmu_close(&fmu);
    return 0;
}
