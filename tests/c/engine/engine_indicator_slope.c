/* Localization from the indicator's slope (ssx_set_indicator_slope), on the seed's pendulum
 * with theta's declared derivative der(theta): the first crossing is found in two trials (the
 * cubic Hermite through the macro step's ends, then a Newton step aimed just past the zero), on
 * the far side within tol_value, and within tol_time of the crossing of the FMU's own
 * trajectory (bisection to 1e-13 as the reference, no slope); with tol_value 0 the bracket
 * itself comes within tol_time. A wrong slope (another variable's) costs trials, never
 * accuracy. A slope for a callback indicator or no indicator is refused. */
#include <math.h>

#include "test_support.h"

enum { PENDULUM_DER_THETA = 3 };

#define TOL_TIME 1e-9
#define REFERENCE_TOL_TIME 1e-13

typedef struct {
    double t;
    int iterations;
    double located_value; /* the indicator at t */
    double width;         /* of the last bracket */
} located;

/* slope: the value reference the indicator's slope is read from, or -1 for none */
static located first_event(const char *stem, ssx_locator locator, double tol_time,
                           double tol_value, int slope)
{
    ssx_fmu *fmu = load_fmu(stem);
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, locator, tol_time, tol_value, &c);
    if (slope >= 0) {
        CHECK_OK(sys, ssx_set_indicator_slope(sys, 0, (unsigned int)slope));
    }
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.05));
    CHECK(ssx_event_count(sys) == 1);
    ssx_event_record event;
    CHECK(ssx_event_get(sys, 0, &event) == 0);
    ssx_localization_trial last;
    CHECK(event.n_trials > 0 &&
          ssx_event_trial(sys, event.first_trial + (size_t)event.n_trials - 1, &last) == 0);
    located found = {.t = event.t, .iterations = event.iterations, .width = last.b - last.a,
                     .located_value = last.t == event.t ? last.value : event.value_right};
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
    return found;
}

static void two_trials_at_the_crossing(const char *stem)
{
    located reference = first_event(stem, SSX_BISECTION, REFERENCE_TOL_TIME, 0.0, -1);
    located values = first_event(stem, SSX_ILLINOIS, TOL_TIME, 1e-9, -1);
    located sloped = first_event(stem, SSX_ILLINOIS, TOL_TIME, 1e-9, PENDULUM_DER_THETA);
    located bracketed = first_event(stem, SSX_ILLINOIS, TOL_TIME, 0.0, PENDULUM_DER_THETA);
    printf("%s: crossing %.17g; trials from values %d, from the slope %d (%+.3g s, theta "
           "%.3g), with tol_value 0 %d (bracket %.3g)\n",
           stem, reference.t, values.iterations, sloped.iterations, sloped.t - reference.t,
           sloped.located_value, bracketed.iterations, bracketed.width);
    CHECK(reference.width <= REFERENCE_TOL_TIME);
    CHECK(sloped.iterations <= 2 && sloped.iterations < values.iterations);
    /* the far side, within tol_value, and within tol_time of the crossing */
    CHECK(sloped.located_value < 0.0 && sloped.located_value >= -1e-9);
    CHECK(sloped.t >= reference.t - REFERENCE_TOL_TIME && sloped.t - reference.t <= TOL_TIME);
    CHECK(bracketed.width <= TOL_TIME && bracketed.iterations <= 4);
    CHECK(fabs(bracketed.t - reference.t) <= TOL_TIME);
    /* theta's own value and the angular acceleration as its slope: wrong, and harmless */
    const int wrong[] = {PENDULUM_THETA, PENDULUM_ALPHA};
    for (int k = 0; k < 2; ++k) {
        for (int with_value = 0; with_value < 2; ++with_value) {
            located misled =
                first_event(stem, SSX_ILLINOIS, TOL_TIME, with_value ? 1e-9 : 0.0, wrong[k]);
            /* halving 0.05 to 1e-9 takes 26 trials: the budget is two more */
            CHECK(misled.iterations <= 28);
            CHECK(misled.t >= reference.t - REFERENCE_TOL_TIME &&
                  misled.t - reference.t <= TOL_TIME);
            CHECK(misled.width <= TOL_TIME ||
                  (misled.located_value < 0.0 && misled.located_value >= -1e-9));
            printf("  slope from value reference %d, tol_value %g: %d trials\n", wrong[k],
                   with_value ? 1e-9 : 0.0, misled.iterations);
        }
    }
}

static int never_crosses(void *user, double t, double *value)
{
    (void)user;
    (void)t;
    *value = 1.0;
    return 0;
}

static void refused_where_no_fmu_variable_gives_it(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    int c;
    ssx_system *sys = seed_pendulum_system(fmu, SSX_ILLINOIS, TOL_TIME, 1e-9, &c);
    int callback = ssx_add_indicator_callback(sys, c, never_crosses, NULL, 0);
    CHECK(callback == 1);
    CHECK(ssx_set_indicator_slope(sys, callback, PENDULUM_DER_THETA) == -1);
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_CONFIG);
    CHECK(strstr(ssx_last_error(sys)->message, "Pendulum_CVODE") != NULL);
    CHECK(ssx_set_indicator_slope(sys, 2, PENDULUM_DER_THETA) == -1);
    CHECK(strstr(ssx_last_error(sys)->message, "no indicator 2") != NULL);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    two_trials_at_the_crossing("pendulum_euler");
    two_trials_at_the_crossing("pendulum_cvode");
    refused_where_no_fmu_variable_gives_it();
    return 0;
}
