/* Pendulum with wall contact (internal event) against the exact impact times.
 * Usage: test_fmu_contact <binary> <modelDescription.xml> euler|cvode */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fmu_harness.h"

#define STIFFNESS (40.0 * 9.81 * 0.6 / 20.0) /* m g L / I */
#define CONTACTS 5
#define EULER_STEP 1e-4 /* the FMU's default euler_step_size */

static int is_positive(double value)
{
    return value > 0.0;
}

static int is_negative(double value)
{
    return value < 0.0;
}

/* Impact k+1 follows impact k after a rise from the wall to the new amplitude and back, half a
 * period 2 K(sin^2(a/2)) / w; each impact scales sin(a/2) by the restitution (energy). */
static void exact_impacts(double theta0, double restitution, double times[CONTACTS])
{
    double w = sqrt(STIFFNESS);
    double s = sin(fabs(theta0) / 2.0);
    times[0] = elliptic_k(s * s) / w;
    for (int k = 1; k < CONTACTS; ++k) {
        s *= restitution;
        times[k] = times[k - 1] + 2.0 * elliptic_k(s * s) / w;
    }
}

static fmi2Component start(test_fmu *fmu, int cvode, double theta0, double wall, int sense,
                           double restitution)
{
    const char *names[] = {"theta0", "theta_wall", "restitution"};
    const double values[] = {theta0, wall, restitution};
    fmi2Component c = fmu->instantiate("contact", fmi2CoSimulation, fmu->guid, "",
                                       &fmu->callbacks, fmi2False, fmi2False);
    CHECK(c != NULL);
    CHECK_OK(fmu->setup_experiment(c, cvode, 1e-10, 0.0, fmi2False, 0.0));
    CHECK_OK(fmu->enter_initialization_mode(c));
    for (int i = 0; i < 3; ++i)
        fmu_set(fmu, c, names[i], values[i]);
    fmi2ValueReference sense_vr = fmu_vr(fmu, "sense");
    CHECK_OK(fmu->set_integer(c, &sense_vr, 1, &sense));
    CHECK_OK(fmu->exit_initialization_mode(c));
    return c;
}

/* Impacts are where omega jumps to the side away from the wall; turning points lie between. */
static void check_impacts(test_fmu *fmu, int cvode, double theta0, int sense, double restitution)
{
    double expected[CONTACTS];
    exact_impacts(theta0, restitution, expected);
    fmi2Component c = start(fmu, cvode, theta0, 0.0, sense, restitution);
    value_predicate away = sense < 0 ? is_positive : is_negative;
    value_predicate back = sense < 0 ? is_negative : is_positive;
    double t = 0.0, dt = 1e-3;
    for (int k = 0; k < CONTACTS; ++k) {
        double impact = fmu_find_time(fmu, c, t, dt, 10.0, "omega", away, 1e-12, &t);
        char label[96];
        snprintf(label, sizeof label, "impact %d (restitution %g, sense %+d) [s]", k + 1,
                 restitution, sense);
        /* CVODE at rtol 1e-10 over about 4 s. Explicit Euler gains energy by a factor
         * (1 + h^2 w^2) per step, so amplitude and period drift and the phase error grows like
         * h w^2 t^2 (2e-6 at the first impact, as in the seed): bound h w^2 t^2 / 40. */
        double euler_bound = EULER_STEP * STIFFNESS * expected[k] * expected[k] / 40.0;
        CHECK_NEAR(label, impact, expected[k], cvode ? 1e-8 : euler_bound);
        CHECK_NEAR("theta right after the impact [rad]", fmu_get(fmu, c, "theta"), 0.0, 1e-8);
        if (k + 1 < CONTACTS)
            fmu_find_time(fmu, c, t, dt, 10.0, "omega", back, 1e-6, &t);
    }
    fmu->free_instance(c);
}

/* A wall that gravity pushes into: the bounces shrink geometrically and, once a rebound cannot
 * leave the band gap_tol, the pendulum rests at the wall instead of chattering. */
static void check_rest_at_wall(test_fmu *fmu, int cvode)
{
    fmi2Component c = start(fmu, cvode, 0.5, 0.1, -1, 0.5);
    for (int k = 0; k < 100; ++k)
        CHECK_OK(fmu->do_step(c, k * 0.1, 0.1, fmi2False));
    CHECK_NEAR("theta at rest [rad]", fmu_get(fmu, c, "theta"), 0.1, 0.0);
    CHECK_NEAR("omega at rest [rad/s]", fmu_get(fmu, c, "omega"), 0.0, 0.0);
    fmi2ValueReference contact = fmu_vr(fmu, "contact");
    fmi2Boolean touching = fmi2False;
    CHECK_OK(fmu->get_boolean(c, &contact, 1, &touching));
    CHECK(touching == fmi2True);
    fmu->free_instance(c);
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
    check_impacts(&fmu, cvode, 0.5, -1, 1.0);
    check_impacts(&fmu, cvode, -0.5, +1, 1.0);
    check_impacts(&fmu, cvode, 0.5, -1, 0.5);
    check_rest_at_wall(&fmu, cvode);
    fmu_close(&fmu);
    return 0;
}
