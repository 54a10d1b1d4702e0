/* Pendulum FMU (Euler or CVODE back-end) against the exact solution, and its state API.
 * Usage: test_fmu_pendulum <binary> <modelDescription.xml> euler|cvode */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_harness.h"

#define THETA0 0.5
/* m g L / I for the default parameters m = 40, g = 9.81, L = 0.6, I = 20 */
#define STIFFNESS (40.0 * 9.81 * 0.6 / 20.0)

static int is_not_positive(double value)
{
    return value <= 0.0;
}

static double exact_quarter_period(void)
{
    double s = sin(THETA0 / 2.0);
    return elliptic_k(s * s) / sqrt(STIFFNESS);
}

static fmi2Component start_pendulum(test_fmu *fmu, int cvode, double t0)
{
    const char *names[] = {"theta0", "omega0"};
    const double values[] = {THETA0, 0.0};
    /* CVODE at rtol 1e-10; Euler at its default internal step 1e-4 */
    return fmu_start(fmu, cvode ? 1e-10 : 0.0, t0, names, values, 2);
}

/* The first downward zero crossing of theta, to 1e-12 s by state bisection. */
static void check_quarter_period(test_fmu *fmu, int cvode)
{
    fmi2Component c = start_pendulum(fmu, cvode, 0.0);
    double t_now;
    double crossing = fmu_find_time(fmu, c, 0.0, cvode ? 1e-2 : 1e-4, 1.0, "theta",
                                    is_not_positive, 1e-12, &t_now);
    /* CVODE at rtol 1e-10 is far more accurate than 1e-8; explicit Euler at h = 1e-4 lands
     * 2e-6 late (first order: the error is of order h times the swing's time scale). */
    CHECK_NEAR("first zero crossing of theta [s]", crossing, exact_quarter_period(),
               cvode ? 1e-8 : 5e-6);
    if (!cvode) /* the Euler result the seed tutorial printed, to its 8 digits */
        CHECK_NEAR("Euler crossing vs the seed's 0.46507956", crossing, 0.46507956, 5e-9);
    fmu->free_instance(c);
}

/* Energy is conserved: at t = 3 s, 0.5 I omega^2 + m g L (1 - cos theta) must be unchanged. */
static void check_energy(test_fmu *fmu, int cvode)
{
    fmi2Component c = start_pendulum(fmu, cvode, 0.0);
    for (int k = 0; k < 300; ++k)
        CHECK_OK(fmu->do_step(c, k * 0.01, 0.01, fmi2False));
    double theta = fmu_get(fmu, c, "theta"), omega = fmu_get(fmu, c, "omega");
    double energy = 0.5 * omega * omega + STIFFNESS * (1.0 - cos(theta));
    double initial = STIFFNESS * (1.0 - cos(THETA0));
    /* Euler gains energy by a factor (1 + h^2 w^2) per step: about 3e-3 relative over 3 s.
     * BDF's global error is some tens of times its local tolerance 1e-10. */
    CHECK_NEAR("energy per inertia at t = 3 s [1/s2]", energy, initial,
               (cvode ? 5e-8 : 5e-3) * initial);
    fmu->free_instance(c);
}

/* Setting the torque changes alpha at once, without a step (direct feedthrough). */
static void check_feedthrough(test_fmu *fmu, int cvode)
{
    fmi2Component c = start_pendulum(fmu, cvode, 0.0);
    CHECK_OK(fmu->do_step(c, 0.0, 0.1, fmi2False));
    double theta = fmu_get(fmu, c, "theta");
    fmu_set(fmu, c, "torque", 7.0);
    CHECK_NEAR("alpha right after setting the torque", fmu_get(fmu, c, "alpha"),
               -STIFFNESS * sin(theta) + 7.0 / 20.0, 1e-15);
    fmu->free_instance(c);
}

static void run_to(test_fmu *fmu, fmi2Component c, double t_from, double t_to, double dt)
{
    long steps = lround((t_to - t_from) / dt);
    for (long k = 0; k < steps; ++k)
        CHECK_OK(fmu->do_step(c, t_from + k * dt, dt, fmi2False));
}

/* The FMU serves gets from the outputs its last doStep computed; every other change of inputs,
 * state or parameters must make the next get recompute them. */
static void check_outputs_follow_every_change(test_fmu *fmu, int cvode)
{
    fmi2Component c = start_pendulum(fmu, cvode, 0.0);
    CHECK_NEAR("alpha after initialization", fmu_get(fmu, c, "alpha"),
               -STIFFNESS * sin(THETA0), 1e-15);
    run_to(fmu, c, 0.0, 0.2, 0.01);
    double theta = fmu_get(fmu, c, "theta");
    double alpha = fmu_get(fmu, c, "alpha");
    CHECK_NEAR("alpha after steps", alpha, -STIFFNESS * sin(theta), 1e-15);
    const double pushed = -STIFFNESS * sin(theta) + 7.0 / 20.0; /* alpha with torque 7 */

    fmu_set(fmu, c, "torque", 7.0);
    /* taken before any get: the state holds the torque but not yet the alpha that follows */
    fmi2FMUstate state = NULL;
    CHECK_OK(fmu->get_state(c, &state));
    CHECK_NEAR("alpha after setting the torque", fmu_get(fmu, c, "alpha"), pushed, 1e-15);
    fmu_set(fmu, c, "torque", 7.0);
    CHECK_NEAR("alpha after setting the same torque again", fmu_get(fmu, c, "alpha"), pushed,
               1e-15);
    fmu_set(fmu, c, "torque", 0.0);
    CHECK_NEAR("alpha after setting the torque back to 0", fmu_get(fmu, c, "alpha"), alpha, 0.0);
    run_to(fmu, c, 0.2, 0.5, 0.01);
    CHECK(fmu_get(fmu, c, "theta") != theta);

    CHECK_OK(fmu->set_state(c, state));
    CHECK_NEAR("theta after setting the state back", fmu_get(fmu, c, "theta"), theta, 0.0);
    CHECK_NEAR("alpha after setting the state back (torque 7 again)", fmu_get(fmu, c, "alpha"),
               pushed, 1e-15);
    CHECK_OK(fmu->free_state(c, &state));

    CHECK_OK(fmu->reset(c));
    CHECK_NEAR("alpha after reset (theta0 = 0, torque = 0)", fmu_get(fmu, c, "alpha"), 0.0, 0.0);
    CHECK_OK(fmu->setup_experiment(c, cvode, 1e-10, 0.0, fmi2False, 0.0));
    CHECK_OK(fmu->enter_initialization_mode(c));
    fmu_set(fmu, c, "theta0", THETA0);
    CHECK_NEAR("alpha after setting theta0 in initialization mode", fmu_get(fmu, c, "alpha"),
               -STIFFNESS * sin(THETA0), 1e-15);
    fmu->free_instance(c);
}

/* get state at t1, run to t2, set it back, run to t2 again; also through serialization into
 * a fresh instance. The engine reuses one state buffer: fmi2GetFMUstate must not reallocate. */
static void check_state_round_trip(test_fmu *fmu, int cvode)
{
    const double t1 = 0.2, t2 = 0.7, dt = 0.01;
    fmi2Component c = start_pendulum(fmu, cvode, 0.0);
    run_to(fmu, c, 0.0, t1, dt);
    fmi2FMUstate state = NULL;
    CHECK_OK(fmu->get_state(c, &state));
    fmi2FMUstate reused = state;
    CHECK_OK(fmu->get_state(c, &reused));
    CHECK(reused == state);
    run_to(fmu, c, t1, t2, dt);
    double first[2] = {fmu_get(fmu, c, "theta"), fmu_get(fmu, c, "omega")};

    CHECK_OK(fmu->set_state(c, state));
    CHECK_NEAR("theta after restoring the state at t1", fmu_get(fmu, c, "theta"),
               fmu_get(fmu, c, "theta"), 0.0);
    run_to(fmu, c, t1, t2, dt);
    double second[2] = {fmu_get(fmu, c, "theta"), fmu_get(fmu, c, "omega")};
    /* Euler repeats the same arithmetic; CVODE restarts from t1, agreeing to its tolerance */
    double tolerance = cvode ? 1e-9 : 0.0;
    for (int i = 0; i < 2; ++i)
        CHECK_NEAR(i ? "omega at t2 after set state" : "theta at t2 after set state", second[i],
                   first[i], tolerance * fabs(first[i]));

    size_t size = 0;
    CHECK_OK(fmu->serialized_size(c, state, &size));
    char *bytes = malloc(size);
    CHECK(bytes != NULL);
    CHECK_OK(fmu->serialize(c, state, bytes, size));
    fmi2Component fresh = start_pendulum(fmu, cvode, 0.0);
    fmi2FMUstate copy = NULL;
    CHECK_OK(fmu->deserialize(fresh, bytes, size, &copy));
    CHECK_OK(fmu->set_state(fresh, copy));
    run_to(fmu, fresh, t1, t2, dt);
    CHECK_NEAR("theta at t2 in a fresh instance (deserialized)", fmu_get(fmu, fresh, "theta"),
               second[0], 0.0);
    printf("serialized state: %zu bytes\n", size);
    CHECK_OK(fmu->free_state(fresh, &copy));
    CHECK_OK(fmu->free_state(c, &state));
    CHECK(state == NULL);
    free(bytes);
    fmu->free_instance(fresh);
    fmu->free_instance(c);
}

/* fmi2Reset returns to the start values; the same run then gives the same result. */
static void check_reset(test_fmu *fmu, int cvode)
{
    fmi2Component c = start_pendulum(fmu, cvode, 0.0);
    run_to(fmu, c, 0.0, 0.3, 0.01);
    double before = fmu_get(fmu, c, "theta");
    CHECK_OK(fmu->reset(c));
    CHECK_NEAR("theta after reset (start value theta0 = 0)", fmu_get(fmu, c, "theta"), 0.0, 0.0);
    CHECK_OK(fmu->setup_experiment(c, cvode, 1e-10, 0.0, fmi2False, 0.0));
    CHECK_OK(fmu->enter_initialization_mode(c));
    fmu_set(fmu, c, "theta0", THETA0);
    CHECK_OK(fmu->exit_initialization_mode(c));
    run_to(fmu, c, 0.0, 0.3, 0.01);
    CHECK_NEAR("theta at 0.3 s after reset and rerun", fmu_get(fmu, c, "theta"), before,
               cvode ? 1e-12 : 0.0);
    fmu->free_instance(c);
}

/* What real masters do: zero steps, a communication point off by rounding, and (like the seed's
 * CVODE wrapper) a new instance started mid-run from the current state. */
static void check_master_habits(test_fmu *fmu, int cvode)
{
    fmi2Component c = start_pendulum(fmu, cvode, 0.0);
    run_to(fmu, c, 0.0, 0.25, 0.05);
    double theta = fmu_get(fmu, c, "theta"), omega = fmu_get(fmu, c, "omega");
    CHECK_OK(fmu->do_step(c, 0.25, 0.0, fmi2False));
    CHECK_NEAR("theta after a zero step", fmu_get(fmu, c, "theta"), theta, 0.0);
    CHECK_OK(fmu->do_step(c, 0.25 * (1.0 + 1e-14), 0.05, fmi2False));
    CHECK(fmu->do_step(c, 0.31, 0.05, fmi2False) == fmi2Error); /* the FMU is at 0.30 */

    const char *names[] = {"theta0", "omega0"};
    const double restart[] = {theta, omega};
    fmi2Component again = fmu_start(fmu, cvode ? 1e-10 : 0.0, 0.25, names, restart, 2);
    CHECK_OK(fmu->do_step(again, 0.25, 0.05, fmi2False));
    /* CVODE restarts (tolerance 1e-10); Euler differs only by the 2.5e-15 s rounding of the
     * communication point taken above, times omega. */
    CHECK_NEAR("theta at 0.3 s, restarted at 0.25 s", fmu_get(fmu, again, "theta"),
               fmu_get(fmu, c, "theta"), cvode ? 1e-9 : 1e-13);
    fmu->free_instance(again);
    fmu->free_instance(c);
}

/* Euler covers a communication interval exactly: 2.5e-4 s is two substeps of 1e-4 and a
 * shortened one of 5e-5, the explicit Euler recurrence written out here. */
static void check_euler_substeps(test_fmu *fmu)
{
    fmi2Component c = start_pendulum(fmu, 0, 0.0);
    CHECK_OK(fmu->do_step(c, 0.0, 2.5e-4, fmi2False));
    double theta = THETA0, omega = 0.0;
    const double steps[] = {1e-4, 1e-4, 2.5e-4 - 2e-4};
    for (int i = 0; i < 3; ++i) {
        double alpha = -STIFFNESS * sin(theta);
        theta += steps[i] * omega;
        omega += steps[i] * alpha;
    }
    CHECK_NEAR("theta after 2.5e-4 s of Euler", fmu_get(fmu, c, "theta"), theta, 0.0);
    CHECK_NEAR("omega after 2.5e-4 s of Euler", fmu_get(fmu, c, "omega"), omega, 0.0);
    fmu->free_instance(c);
}

/* CVODE keeps integrating across communication points; only a changed input restarts it, so
 * writing the unchanged torque before every step leaves the run bit-identical, while a changed
 * torque (set away and back) restarts it and the run differs at the level of the tolerance. */
static void check_cvode_restarts_only_on_change(test_fmu *fmu)
{
    double results[3];
    for (int variant = 0; variant < 3; ++variant) {
        fmi2Component c = start_pendulum(fmu, 1, 0.0);
        for (int k = 0; k < 100; ++k) {
            if (variant >= 1)
                fmu_set(fmu, c, "torque", 0.0);
            if (variant == 2 && k == 50) {
                fmu_set(fmu, c, "torque", 1.0);
                fmu_set(fmu, c, "torque", 0.0);
            }
            CHECK_OK(fmu->do_step(c, k * 0.01, 0.01, fmi2False));
        }
        results[variant] = fmu_get(fmu, c, "theta");
        fmu->free_instance(c);
    }
    CHECK_NEAR("theta at 1 s, unchanged torque written each step", results[1], results[0], 0.0);
    CHECK(results[2] != results[0]);
    /* both runs are within 1e-8 of the exact solution (checked against scipy in Python) */
    CHECK_NEAR("theta at 1 s, restarted at 0.5 s", results[2], results[0], 1e-8);
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
    check_quarter_period(&fmu, cvode);
    check_energy(&fmu, cvode);
    check_feedthrough(&fmu, cvode);
    check_outputs_follow_every_change(&fmu, cvode);
    check_state_round_trip(&fmu, cvode);
    check_reset(&fmu, cvode);
    check_master_habits(&fmu, cvode);
    if (cvode)
        check_cvode_restarts_only_on_change(&fmu);
    else
        check_euler_substeps(&fmu);
    fmu_close(&fmu);
    return 0;
}
