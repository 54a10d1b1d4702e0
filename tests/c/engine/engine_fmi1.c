/* FMI 1.0 through the binding's FMI 1.0 back-ends (fmu_fmi1.c), under AddressSanitizer too, on
 * the toolchain's FMI 1.0 builds: Co-Simulation steps the pendulum to the FMI 2.0 build's
 * numbers bit for bit; Model Exchange bounces the ball at the closed-form times; the FMU's log
 * reaches the engine's message; FMI 1.0 has no FMU state; the binding refuses what it cannot
 * load. */
#include <math.h>

#include "test_support.h"

enum { STEPS = 100 };

/* theta over 1 s in steps of 0.01 from theta0 = 0.5, the FMU's own tolerance */
static void pendulum_run(ssx_fmu *fmu, double *theta)
{
    CHECK(start_pendulum(fmu, 0.0, 0.5, 0.0, 0.0) <= 1);
    ssx_system *sys = ssx_system_new("pendulum");
    int c = add_pendulum(sys, "P", fmu);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.01));
    CHECK(ssx_history_length(sys) == STEPS + 1);
    const double *values = ssx_history_values(sys, c);
    size_t width = 3; /* theta, omega, alpha per sample */
    for (size_t k = 0; k <= STEPS; ++k) {
        theta[k] = values[k * width];
    }
    ssx_system_free(sys);
}

static void cosimulation_equals_the_fmi2_build(void)
{
    double fmi1[STEPS + 1], fmi2[STEPS + 1];
    ssx_fmu *fmu = load_fmi1_fmu("pendulum_cvode_fmi1", "pendulum_cvode_fmi1", 0);
    pendulum_run(fmu, fmi1);
    ssx_fmu_free(fmu);
    fmu = load_fmu("pendulum_cvode");
    pendulum_run(fmu, fmi2);
    ssx_fmu_free(fmu);
    CHECK(memcmp(fmi1, fmi2, sizeof fmi1) == 0);
    CHECK(fmi1[STEPS] != fmi1[0]);
}

static void model_exchange_bounces_at_the_closed_form_times(void)
{
    ssx_fmu *fmu = load_fmi1_fmu("bouncing_ball_cvode_fmi1_me", "bouncing_ball_cvode_fmi1", 1);
    CHECK(start_fmu(fmu, 0.0, 1e-12, NULL, NULL, 0) <= 1);
    ssx_system *sys = ssx_system_new("ball");
    int c = ssx_add_model_exchange_component(sys, "Ball", fmu, 0, 2, 1);
    CHECK(c == 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, 0) == 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, 1) == 1);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    check_own_bounces(sys);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static void the_fmus_log_reaches_the_message_and_there_is_no_state(void)
{
    ssx_fmu *fmu = load_fmi1_fmu("pendulum_cvode_fmi1", "pendulum_cvode_fmi1", 0);
    CHECK(start_pendulum(fmu, 0.0, 0.5, 0.0, 0.0) <= 1);
    const unsigned int unknown = 999;
    double value = 0.0;
    CHECK(ssx_fmu_get_real(fmu, &unknown, 1, &value) == 3); /* fmiError */
    CHECK(strcmp(ssx_fmu_last_call(fmu), "fmiGetReal") == 0);
    CHECK(strstr(ssx_fmu_last_message(fmu), "999") != NULL);
    void *state = NULL;
    CHECK(ssx_fmu_get_state(fmu, &state) == -1);
    CHECK(strstr(ssx_fmu_last_message(fmu), "FMI 1.0 Co-Simulation, which has no such function")
          != NULL);
    ssx_fmu_free(fmu);
}

static void refuses_what_it_cannot_load(void)
{
    char error[256];
    ssx_fmu_load_spec spec = {.version = SSX_FMI1, .interface = SSX_MODEL_EXCHANGE,
                              .binary_path = "x.so", .model_identifier = "x",
                              .host_path = "host"};
    CHECK(ssx_fmu_load(&spec, error, sizeof error) == NULL);
    CHECK(strcmp(error, "ssx_fmu_load: only FMI 2.0 and FMI 1.0 Co-Simulation FMUs run in a "
                        "host process") == 0);
    spec = (ssx_fmu_load_spec){.version = 7, .binary_path = "x.so", .model_identifier = "x"};
    CHECK(ssx_fmu_load(&spec, error, sizeof error) == NULL);
    CHECK(strstr(error, "not one syssimx runs") != NULL);
    CHECK(ssx_fmu_load(NULL, error, sizeof error) == NULL);
}

int main(void)
{
    cosimulation_equals_the_fmi2_build();
    model_exchange_bounces_at_the_closed_form_times();
    the_fmus_log_reaches_the_message_and_there_is_no_state();
    refuses_what_it_cannot_load();
    return 0;
}
