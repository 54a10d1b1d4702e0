/* The bouncing ball as Model Exchange, driven by a minimal importer: classical Runge-Kutta (exact
 * for the ball's quadratic flight), each bounce located by bisecting the step over a saved FMU
 * state, then event mode. The importer integrates, so the FMU's own back-end does not matter.
 * Usage: test_fmu_model_exchange <binary> <modelDescription.xml> */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_harness.h"

#define G 9.81
#define E 0.8
#define H0 1.0
#define N_STATES 2
#define STEP 1e-3
#define BOUNCES 5
#define RESOLUTION 1e-13

/* One Runge-Kutta step of length h from the FMU's states at t; leaves the FMU at t + h. */
static void runge_kutta_step(test_fmu *fmu, fmi2Component c, double t, double h)
{
    static const double stage_at[4] = {0.0, 0.5, 0.5, 1.0};
    double x[N_STATES], k[4][N_STATES], y[N_STATES];
    CHECK_OK(fmu->get_continuous_states(c, x, N_STATES));
    for (int s = 0; s < 4; ++s) {
        for (int i = 0; i < N_STATES; ++i)
            y[i] = s == 0 ? x[i] : x[i] + stage_at[s] * h * k[s - 1][i];
        CHECK_OK(fmu->set_time(c, t + stage_at[s] * h));
        CHECK_OK(fmu->set_continuous_states(c, y, N_STATES));
        CHECK_OK(fmu->get_derivatives(c, k[s], N_STATES));
    }
    for (int i = 0; i < N_STATES; ++i)
        y[i] = x[i] + h / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
    CHECK_OK(fmu->set_time(c, t + h));
    CHECK_OK(fmu->set_continuous_states(c, y, N_STATES));
}

static int above_floor(test_fmu *fmu, fmi2Component c)
{
    double z = NAN;
    CHECK_OK(fmu->get_event_indicators(c, &z, 1));
    return z > 0.0;
}

/* Integrates to the next bounce and handles it; returns its time. */
static double next_bounce(test_fmu *fmu, fmi2Component c, double t, fmi2FMUstate *saved)
{
    for (;; t += STEP) {
        CHECK(t < 5.0);
        CHECK_OK(fmu->get_state(c, saved));
        runge_kutta_step(fmu, c, t, STEP);
        if (!above_floor(fmu, c))
            break;
    }
    double low = 0.0, high = STEP;
    while (high - low > RESOLUTION) {
        double middle = 0.5 * (low + high);
        CHECK_OK(fmu->set_state(c, *saved));
        runge_kutta_step(fmu, c, t, middle);
        if (above_floor(fmu, c))
            low = middle;
        else
            high = middle;
    }
    CHECK_OK(fmu->set_state(c, *saved));
    runge_kutta_step(fmu, c, t, high);
    CHECK(!above_floor(fmu, c));
    double before[N_STATES], after[N_STATES];
    CHECK_OK(fmu->get_continuous_states(c, before, N_STATES));
    fmi2EventInfo info;
    CHECK_OK(fmu->enter_event_mode(c));
    CHECK_OK(fmu->new_discrete_states(c, &info));
    CHECK(info.valuesOfContinuousStatesChanged && !info.newDiscreteStatesNeeded);
    CHECK(!info.terminateSimulation && !info.nextEventTimeDefined);
    CHECK_OK(fmu->get_continuous_states(c, after, N_STATES));
    CHECK_NEAR("height after the bounce [m]", after[0], 0.0, 0.0);
    CHECK_NEAR("rebound [m/s]", after[1], -E * before[1], 0.0);
    CHECK_OK(fmu->enter_continuous_time_mode(c));
    return t + high;
}

/* A state taken in continuous-time mode, serialized and restored into a fresh instance, gives
 * the same states and the same mode there; a co-simulation instance refuses it. */
static void check_serialized_state(test_fmu *fmu, fmi2Component c)
{
    fmi2FMUstate state = NULL, copy = NULL;
    size_t size = 0;
    CHECK_OK(fmu->get_state(c, &state));
    CHECK_OK(fmu->serialized_size(c, state, &size));
    char *bytes = malloc(size);
    CHECK(bytes != NULL);
    CHECK_OK(fmu->serialize(c, state, bytes, size));
    fmi2Component fresh = fmu->instantiate("fresh", fmi2ModelExchange, fmu->guid, "",
                                           &fmu->callbacks, fmi2False, fmi2False);
    CHECK(fresh != NULL);
    CHECK_OK(fmu->deserialize(fresh, bytes, size, &copy));
    CHECK_OK(fmu->set_state(fresh, copy));
    double x[N_STATES], y[N_STATES];
    CHECK_OK(fmu->get_continuous_states(c, x, N_STATES));
    CHECK_OK(fmu->get_continuous_states(fresh, y, N_STATES));
    CHECK(memcmp(x, y, sizeof x) == 0);
    CHECK_OK(fmu->set_continuous_states(fresh, y, N_STATES)); /* continuous-time mode */
    CHECK_OK(fmu->free_state(fresh, &copy));
    fmu->free_instance(fresh);

    fmi2Component slave = fmu_start(fmu, 0.0, 0.0, NULL, NULL, 0);
    CHECK(fmu->deserialize(slave, bytes, size, &copy) == fmi2Error);
    CHECK(strstr(fmu->log.last_message, "not a state of this FMU") != NULL);
    fmu->free_instance(slave);
    free(bytes);
    CHECK_OK(fmu->free_state(c, &state));
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s <binary> <modelDescription.xml>\n", argv[0]);
        return 2;
    }
    test_fmu fmu;
    fmu_open(&fmu, argv[1], argv[2]);
    fmi2Component c = fmu.instantiate("test", fmi2ModelExchange, fmu.guid, "", &fmu.callbacks,
                                      fmi2False, fmi2False);
    CHECK(c != NULL);
    CHECK_OK(fmu.setup_experiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    CHECK_OK(fmu.enter_initialization_mode(c));
    CHECK_OK(fmu.exit_initialization_mode(c));
    fmi2EventInfo info;
    CHECK_OK(fmu.new_discrete_states(c, &info));
    CHECK(!info.valuesOfContinuousStatesChanged && !info.nextEventTimeDefined);
    CHECK_OK(fmu.enter_continuous_time_mode(c));

    /* t1 = sqrt(2 h0 / g), then flights of 2 e^k v1 / g with v1 = g t1 */
    double expected = sqrt(2.0 * H0 / G), v1 = G * expected;
    double t = 0.0;
    fmi2FMUstate saved = NULL;
    for (int k = 0; k < BOUNCES; ++k) {
        t = next_bounce(&fmu, c, t, &saved);
        char label[64];
        snprintf(label, sizeof label, "bounce %d [s]", k + 1);
        /* Runge-Kutta is exact for the flight; what remains is the bisection and rounding */
        CHECK_NEAR(label, t, expected, 1e-11);
        expected += 2.0 * pow(E, k + 1) * v1 / G;
    }
    CHECK_OK(fmu.free_state(c, &saved));
    check_serialized_state(&fmu, c);
    CHECK_OK(fmu.terminate(c));
    fmu.free_instance(c);
    fmu_close(&fmu);
    return 0;
}
