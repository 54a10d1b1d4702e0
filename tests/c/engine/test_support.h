/* Shared helpers of the engine's C tests: checks that stop the test at the first failure, and
 * the pendulum FMU set up like the seed tutorial. */
#ifndef SSX_TEST_SUPPORT_H
#define SSX_TEST_SUPPORT_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "syssimx_engine.h"

#define CHECK(condition) do { \
        if (!(condition)) { \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition); \
            exit(1); \
        } \
    } while (0)

#define CHECK_CLOSE(actual, expected, tolerance) do { \
        double actual_ = (actual), expected_ = (expected); \
        if (!(fabs(actual_ - expected_) <= (tolerance))) { \
            fprintf(stderr, "%s:%d: %s = %.17g, expected %.17g within %g (off by %.3g)\n", \
                    __FILE__, __LINE__, #actual, actual_, expected_, (double)(tolerance), \
                    actual_ - expected_); \
            exit(1); \
        } \
    } while (0)

/* Runs an engine call that must succeed; prints the engine's error otherwise. */
#define CHECK_OK(sys, call) do { \
        if ((call) != 0) { \
            fprintf(stderr, "%s:%d: %s failed: %s\n", __FILE__, __LINE__, #call, \
                    ssx_last_error(sys)->message); \
            exit(1); \
        } \
    } while (0)

/* The system's last error message contains text. */
#define CHECK_MESSAGE(sys, text) do { \
        const char *message_ = ssx_last_error(sys)->message; \
        if (strstr(message_, (text)) == NULL) { \
            fprintf(stderr, "%s:%d: error message \"%s\" lacks \"%s\"\n", __FILE__, __LINE__, \
                    message_, (text)); \
            exit(1); \
        } \
    } while (0)

/* Value references of the pendulum FMUs (models/Pendulum/pendulum.c). */
enum {
    PENDULUM_THETA = 0,
    PENDULUM_OMEGA = 1,
    PENDULUM_ALPHA = 2,
    PENDULUM_TORQUE = 4,
    PENDULUM_THETA0 = 7,
    PENDULUM_OMEGA0 = 8,
};

/* Quarter period of the seed's pendulum (theta0 = 0.5, m g L / I = 11.772):
 * K(sin^2(0.25)) / sqrt(11.772), scipy's ellipk. */
#define PENDULUM_QUARTER_PERIOD 0.46507759431173046

/* The bouncing balls (models/BouncingBall, BouncingBallContinuous) dropped from 1 m at rest
 * under g = 9.81: the time of impact k = 1, 2, ... when each rebound keeps `restitution` of
 * the impact speed. */
#define BALL_GRAVITY 9.81
double ball_bounce_time(int k, double restitution);
/* A system whose component 0 is the Model Exchange bouncing ball (restitution 0.8) run from 0
 * to 3 s in steps of 0.01: its six bounces are its own state events, each within 1e-8 of the
 * closed form at micro step 0, with no rollback and one integration per step (300). */
void check_own_bounces(ssx_system *sys);

/* Loads one of the built FMUs by its stem (e.g. "pendulum_cvode"); exits on failure. */
ssx_fmu *load_fmu(const char *stem);
/* The same, its binding made in `pool` (ssx_fmu_load_spec.binding_pool). */
ssx_fmu *load_fmu_in(const char *stem, ssx_binding_pool *pool);
/* The same FMU loaded for its Model Exchange interface. */
ssx_fmu *load_model_exchange_fmu(const char *stem);
/* One of the FMI 3.0 builds (e.g. "bouncing_ball_cvode_fmi3") with its variables' types, for
 * Co-Simulation or Model Exchange; exits on failure. */
ssx_fmu *load_fmi3_fmu(const char *stem, const ssx_fmi3_variables *variables, int model_exchange);
/* One of the FMI 1.0 builds (e.g. "pendulum_cvode_fmi1", or "..._fmi1_me" for Model Exchange),
 * loaded with the model identifier of its binary; exits on failure. */
ssx_fmu *load_fmi1_fmu(const char *stem, const char *model_identifier, int model_exchange);
/* ssx_fmu_initialize at time t with n Real start values (tolerance <= 0 leaves the tolerance
 * undefined). Returns its status: 0 (or 1, a warning) when the FMU is ready to step. */
int start_fmu(ssx_fmu *fmu, double t, double tolerance, const unsigned int *vr,
              const double *values, size_t n);
/* Instantiates and initializes a pendulum at time t with the given initial state.
 * tolerance <= 0 leaves the tolerance undefined. Returns the first failing fmi2 status or 0. */
int start_pendulum(ssx_fmu *fmu, double t, double theta0, double omega0, double tolerance);
/* Adds the pendulum as a component: outputs theta, omega, alpha; input torque (start 0). */
int add_pendulum(ssx_system *sys, const char *name, ssx_fmu *fmu);

/* The seed's scenario: the pendulum started at theta0 = 0.5 (CVODE rtol 1e-10) as the only
 * component, with indicator 0 on theta falling through zero, hybrid options tol_time, tol_value
 * and locator. Writes the component index to *component. */
ssx_system *seed_pendulum_system(ssx_fmu *fmu, ssx_locator locator, double tol_time,
                                 double tol_value, int *component);

/* The seed's wall, declared: indicator 0 restarts `pendulum` (CVODE rtol 1e-10) from its theta
 * and reversed omega (ssx_set_restart_handler with an event connection). */
void add_wall_restart(ssx_system *sys, int pendulum);

/* The seed's wall: handle_events hook that restarts the pendulum at the event with the
 * velocity reversed (a fresh instance, like the tutorial's FMUPendulum). */
typedef struct {
    ssx_system *sys;
    ssx_fmu *fmu;
    int component;
    int calls;
} wall_bounce;
int reverse_velocity(void *user, const int *indicators, int n, double t);

#endif
