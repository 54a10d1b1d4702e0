/* A single pendulum stepped by the engine equals a bare fmi2 loop on the same grid, bit for bit,
 * and costs exactly one fmi2DoStep per grid interval. */
#include <math.h>

#include "test_support.h"

static void compare(const char *stem, double t0, double tf, double dt, size_t expected_samples)
{
    ssx_fmu *engine_fmu = load_fmu(stem);
    ssx_fmu *bare_fmu = load_fmu(stem);
    CHECK(start_pendulum(engine_fmu, t0, 0.5, 0.0, 1e-10) == 0);
    CHECK(start_pendulum(bare_fmu, t0, 0.5, 0.0, 1e-10) == 0);

    ssx_system *sys = ssx_system_new("bare loop");
    int c = add_pendulum(sys, "pendulum", engine_fmu);
    CHECK_OK(sys, ssx_initialize(sys, t0));
    CHECK_OK(sys, ssx_run(sys, t0, tf, dt));

    size_t n = ssx_history_length(sys);
    CHECK(n == expected_samples);
    const double *time = ssx_history_time(sys);
    const double *values = ssx_history_values(sys, c);
    const unsigned int vr[] = {PENDULUM_THETA, PENDULUM_OMEGA, PENDULUM_ALPHA};
    double bare[3];
    CHECK(ssx_fmu_get_real(bare_fmu, vr, 3, bare) == 0);
    for (int k = 0; k < 3; ++k) {
        CHECK(values[k] == bare[k]);
    }
    for (size_t row = 1; row < n; ++row) {
        CHECK(ssx_fmu_do_step(bare_fmu, time[row - 1], time[row] - time[row - 1], 1) == 0);
        CHECK(ssx_fmu_get_real(bare_fmu, vr, 3, bare) == 0);
        for (int k = 0; k < 3; ++k) {
            CHECK(values[row * 3 + (size_t)k] == bare[k]);
        }
    }

    ssx_fmu_counters counters;
    ssx_fmu_get_counters(engine_fmu, &counters);
    CHECK(counters.do_step == (long)(expected_samples - 1));
    CHECK(counters.get_state == 0 && counters.set_state == 0);
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(stats.do_step_calls == (long)(expected_samples - 1));
    CHECK(stats.macro_steps == (long)(expected_samples - 1));
    CHECK(stats.events == 0 && stats.state_saves == 0);

    ssx_system_free(sys);
    ssx_fmu_free(engine_fmu);
    ssx_fmu_free(bare_fmu);
}

/* The history of 100 FMUs x 3 outputs is reserved for the grid up front: within 1.2x of the
 * raw float64 size (time axis plus outputs). */
static void history_size(void)
{
    enum { COMPONENTS = 100, STEPS = 10000 };
    ssx_fmu *fmus[COMPONENTS];
    ssx_system *sys = ssx_system_new("history size");
    for (int i = 0; i < COMPONENTS; ++i) {
        char name[32];
        snprintf(name, sizeof name, "pendulum%d", i);
        fmus[i] = load_fmu("pendulum_euler");
        CHECK(start_pendulum(fmus[i], 0.0, 0.5, 0.0, 0.0) == 0);
        add_pendulum(sys, name, fmus[i]);
    }
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, STEPS * 1e-4, 1e-4));
    CHECK(ssx_history_length(sys) == STEPS + 1);
    double raw = (double)(STEPS + 1) * (3.0 * COMPONENTS + 1.0) * sizeof(double);
    CHECK((double)ssx_history_bytes(sys) <= 1.2 * raw);
    ssx_system_free(sys);
    for (int i = 0; i < COMPONENTS; ++i) {
        ssx_fmu_free(fmus[i]);
    }
}

/* alpha of the default pendulum (m g L / I = 40 * 9.81 * 0.6 / 20, I = 20) at theta and torque */
static double pendulum_alpha(double theta, double torque)
{
    return -(40.0 * 9.81 * 0.6 / 20.0) * sin(theta) + torque / 20.0;
}

/* The engine skips writing inputs the FMU already holds; a value set in the FMU by anything
 * else (a direct fmi2SetReal, a restored FMU state) must still be overwritten by the next write. */
static void inputs_reach_the_fmu(void)
{
    const unsigned int torque_vr[] = {PENDULUM_TORQUE}, alpha_vr[] = {PENDULUM_ALPHA};
    const unsigned int theta_vr[] = {PENDULUM_THETA};
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    CHECK(start_pendulum(fmu, 0.0, 0.5, 0.0, 0.0) == 0);
    ssx_system *sys = ssx_system_new("inputs");
    int c = add_pendulum(sys, "pendulum", fmu);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.1, 0.01));
    double theta = 0.0, alpha = 0.0;
    CHECK(ssx_fmu_get_real(fmu, theta_vr, 1, &theta) == 0);

    const double five = 5.0;
    CHECK(ssx_fmu_set_real(fmu, torque_vr, 1, &five) == 0);
    CHECK_OK(sys, ssx_component_write_inputs(sys, c));
    CHECK(ssx_fmu_get_real(fmu, alpha_vr, 1, &alpha) == 0);
    CHECK_CLOSE(alpha, pendulum_alpha(theta, 0.0), 1e-15); /* the engine's 0 again */

    double *inputs = ssx_inputs(sys, c);
    inputs[0] = 3.0;
    CHECK_OK(sys, ssx_component_write_inputs(sys, c));
    CHECK(ssx_fmu_get_real(fmu, alpha_vr, 1, &alpha) == 0);
    CHECK_CLOSE(alpha, pendulum_alpha(theta, 3.0), 1e-15);

    CHECK_OK(sys, ssx_component_snapshot(sys, c, 0)); /* the FMU state holds torque 3 */
    inputs[0] = 1.0;
    CHECK_OK(sys, ssx_component_write_inputs(sys, c));
    CHECK_OK(sys, ssx_component_restore(sys, c, 0, 0.1)); /* torque 3 in the FMU, 1 in the engine */
    CHECK_OK(sys, ssx_component_write_inputs(sys, c));
    CHECK(ssx_fmu_get_real(fmu, alpha_vr, 1, &alpha) == 0);
    CHECK_CLOSE(alpha, pendulum_alpha(theta, 1.0), 1e-15);

    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    inputs_reach_the_fmu();
    history_size();
    compare("pendulum_euler", 0.0, 1.0, 0.01, 101);
    compare("pendulum_cvode", 0.0, 1.0, 0.05, 21);
    compare("pendulum_cvode", 0.25, 1.0, 0.07, 12); /* 10 full steps and a shorter last one */
    return 0;
}
