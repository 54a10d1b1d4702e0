/* Helpers of the engine's C tests. */
#include "test_support.h"

#include <math.h>

#include <string.h>

#include "engine_test_fmus.h"

typedef struct {
    const char *stem;
    const char *binary;
    const char *guid;
} built_fmu;

static const built_fmu built_fmus[] = {ENGINE_TEST_FMUS};

static const built_fmu *built(const char *stem)
{
    for (size_t i = 0; i < sizeof built_fmus / sizeof built_fmus[0]; ++i) {
        if (strcmp(built_fmus[i].stem, stem) == 0) {
            return &built_fmus[i];
        }
    }
    fprintf(stderr, "the FMU %s was not built\n", stem);
    exit(1);
}

static ssx_fmu *loaded(ssx_fmu *fmu, const char *stem, const char *error)
{
    if (fmu == NULL) {
        fprintf(stderr, "cannot load %s: %s\n", stem, error);
        exit(1);
    }
    return fmu;
}

static ssx_fmu *load_as(const char *stem, int model_exchange, ssx_binding_pool *pool)
{
    const built_fmu *b = built(stem);
    char error[512];
    ssx_fmu_load_spec spec = {.version = SSX_FMI2,
                              .interface = model_exchange ? SSX_MODEL_EXCHANGE : SSX_CO_SIMULATION,
                              .binary_path = b->binary, .model_identifier = stem,
                              .guid = b->guid, .resource_location = "", .instance_name = stem,
                              .binding_pool = pool};
    return loaded(ssx_fmu_load(&spec, error, sizeof error), stem, error);
}

ssx_fmu *load_fmu_in(const char *stem, ssx_binding_pool *pool)
{
    return load_as(stem, 0, pool);
}

ssx_fmu *load_fmi3_fmu(const char *stem, const ssx_fmi3_variables *variables, int model_exchange)
{
    const built_fmu *b = built(stem);
    char error[512];
    ssx_fmu_load_spec spec = {.version = SSX_FMI3,
                              .interface = model_exchange ? SSX_MODEL_EXCHANGE : SSX_CO_SIMULATION,
                              .binary_path = b->binary, .model_identifier = stem,
                              .guid = b->guid, .resource_location = "", .instance_name = stem,
                              .fmi3_variables = variables};
    return loaded(ssx_fmu_load(&spec, error, sizeof error), stem, error);
}

ssx_fmu *load_fmi1_fmu(const char *stem, const char *model_identifier, int model_exchange)
{
    const built_fmu *b = built(stem);
    char error[512];
    ssx_fmu_load_spec spec = {.version = SSX_FMI1,
                              .interface = model_exchange ? SSX_MODEL_EXCHANGE : SSX_CO_SIMULATION,
                              .binary_path = b->binary, .model_identifier = model_identifier,
                              .guid = b->guid, .resource_location = "", .instance_name = stem};
    return loaded(ssx_fmu_load(&spec, error, sizeof error), stem, error);
}

ssx_fmu *load_fmu(const char *stem)
{
    return load_as(stem, 0, NULL);
}

ssx_fmu *load_model_exchange_fmu(const char *stem)
{
    return load_as(stem, 1, NULL);
}

int start_fmu(ssx_fmu *fmu, double t, double tolerance, const unsigned int *vr,
              const double *values, size_t n)
{
    const ssx_fmu_experiment experiment = {.start_time = t, .tolerance_defined = tolerance > 0,
                                           .tolerance = tolerance};
    const ssx_fmu_values starts = {.real_vr = vr, .real_values = values, .n_real = n};
    return ssx_fmu_initialize(fmu, &experiment, &starts, NULL, NULL);
}

int start_pendulum(ssx_fmu *fmu, double t, double theta0, double omega0, double tolerance)
{
    const unsigned int vr[] = {PENDULUM_THETA0, PENDULUM_OMEGA0};
    const double values[] = {theta0, omega0};
    return start_fmu(fmu, t, tolerance, vr, values, 2);
}

int add_pendulum(ssx_system *sys, const char *name, ssx_fmu *fmu)
{
    int c = ssx_add_fmu_component(sys, name, fmu, 1);
    CHECK(c >= 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, PENDULUM_THETA) == 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, PENDULUM_OMEGA) == 1);
    CHECK(ssx_add_output(sys, c, SSX_REAL, PENDULUM_ALPHA) == 2);
    CHECK(ssx_add_input(sys, c, SSX_REAL, PENDULUM_TORQUE, 0.0) == 0);
    return c;
}

ssx_system *seed_pendulum_system(ssx_fmu *fmu, ssx_locator locator, double tol_time,
                                 double tol_value, int *component)
{
    CHECK(start_pendulum(fmu, 0.0, 0.5, 0.0, 1e-10) == 0);
    ssx_system *sys = ssx_system_new("hybrid pendulum");
    *component = add_pendulum(sys, "Pendulum_CVODE", fmu);
    CHECK(ssx_add_indicator_output(sys, *component, 0, -1) == 0);
    CHECK_OK(sys, ssx_set_hybrid_options(sys, tol_time, tol_value, 100, 10, 0, locator, 0.0));
    return sys;
}

void add_wall_restart(ssx_system *sys, int pendulum)
{
    const ssx_fmu_experiment experiment = {.tolerance_defined = 1, .tolerance = 1e-10};
    const unsigned int start_vr[] = {PENDULUM_THETA0, PENDULUM_OMEGA0};
    const int source[] = {0, 1};
    const double scale[] = {1.0, -1.0}, offset[] = {0.0, 0.0};
    CHECK_OK(sys, ssx_set_restart_handler(sys, pendulum, &experiment, NULL, start_vr, source,
                                          scale, offset, 2));
    CHECK_OK(sys, ssx_add_event_connection(sys, 0, pendulum));
}

int reverse_velocity(void *user, const int *indicators, int n, double t)
{
    wall_bounce *b = user;
    if (n != 1 || indicators[0] != 0) {
        return -1;
    }
    const double *out = ssx_outputs(b->sys, b->component);
    b->calls++;
    return start_pendulum(b->fmu, t, out[0], -out[1], 1e-10) == 0 ? 0 : -1;
}

double ball_bounce_time(int k, double restitution)
{
    double v1 = sqrt(2.0 * BALL_GRAVITY);
    double t = v1 / BALL_GRAVITY;
    for (int j = 1; j < k; ++j) {
        t += 2.0 * pow(restitution, j) * v1 / BALL_GRAVITY;
    }
    return t;
}

void check_own_bounces(ssx_system *sys)
{
    CHECK_OK(sys, ssx_run(sys, 0.0, 3.0, 0.01));
    CHECK(ssx_event_count(sys) == 6);
    for (int k = 1; k <= 6; ++k) {
        ssx_event_record event;
        CHECK(ssx_event_get(sys, (size_t)k - 1, &event) == 0);
        CHECK(event.own == SSX_OWN_STATE_EVENT && event.micro == 0 && event.component == 0);
        CHECK_CLOSE(event.t, ball_bounce_time(k, 0.8), 1e-8);
    }
    ssx_statistics statistics;
    ssx_get_statistics(sys, &statistics);
    CHECK(statistics.own_events == 6 && statistics.state_restores == 0);
    CHECK(statistics.do_step_calls == 300);
}
