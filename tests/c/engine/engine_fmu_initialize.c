/* ssx_fmu_initialize: the whole initialization sequence as one engine call.
 * - start values are written by type in initialization mode and reach the model;
 * - the callback runs in initialization mode, after the start values, and may write more;
 * - a failing step ends the sequence: its status is returned and ssx_fmu_last_call names it;
 * - the status names Python shows come from the engine. */
#include <math.h>
#include <string.h>

#include "test_support.h"

enum { GAIN_Y = 0, GAIN_U = 1, GAIN_K = 2 };

static double output(ssx_fmu *fmu)
{
    const unsigned int y = GAIN_Y;
    double value = NAN;
    CHECK(ssx_fmu_get_real(fmu, &y, 1, &value) == 0);
    return value;
}

typedef struct {
    ssx_fmu *fmu;
    double k_seen; /* k when the callback ran: the start values came first */
    int fail;
} during_init;

static int double_the_gain(void *user)
{
    during_init *d = user;
    const unsigned int k = GAIN_K;
    CHECK(ssx_fmu_get_real(d->fmu, &k, 1, &d->k_seen) == 0);
    const double doubled = 2.0 * d->k_seen;
    return d->fail ? -1 : ssx_fmu_set_real(d->fmu, &k, 1, &doubled);
}

static void writes_starts_then_calls_back(void)
{
    ssx_fmu *fmu = load_fmu("gain");
    const unsigned int vr[] = {GAIN_U, GAIN_K};
    const double values[] = {3.0, 1.5};
    const ssx_fmu_experiment experiment = {.start_time = 0.25};
    const ssx_fmu_values starts = {.real_vr = vr, .real_values = values, .n_real = 2};
    CHECK(ssx_fmu_initialize(fmu, &experiment, &starts, NULL, NULL) == 0);
    CHECK_CLOSE(output(fmu), 4.5, 0.0);
    CHECK(ssx_fmu_do_step(fmu, 0.25, 0.25, 1) == 0); /* in step mode, at the start time */

    void *state = NULL;
    CHECK(ssx_fmu_get_state(fmu, &state) == 0);

    /* the live instance is reset, not replaced: its FMU state stays valid */
    during_init d = {.fmu = fmu};
    CHECK(ssx_fmu_initialize(fmu, &experiment, &starts, double_the_gain, &d) == 0);
    CHECK_CLOSE(d.k_seen, 1.5, 0.0);
    CHECK_CLOSE(output(fmu), 9.0, 0.0);
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(fmu, &counters);
    /* per initialization one write of the starts (one type), the callback's one */
    CHECK(counters.instantiate == 1 && counters.reset == 1 && counters.set_values == 3 &&
          counters.do_step == 1);
    CHECK(ssx_fmu_set_state(fmu, state) == 0);
    CHECK_CLOSE(output(fmu), 4.5, 0.0);
    CHECK(ssx_fmu_free_state(fmu, &state) == 0);
    ssx_fmu_free(fmu);
}

static void stops_at_the_failing_call(void)
{
    ssx_fmu *fmu = load_fmu("gain");
    const ssx_fmu_experiment experiment = {.start_time = 0.0};
    const unsigned int unknown = 999;
    const double value = 1.0;
    const ssx_fmu_values starts = {.real_vr = &unknown, .real_values = &value, .n_real = 1};
    during_init d = {.fmu = fmu};
    int status = ssx_fmu_initialize(fmu, &experiment, &starts, double_the_gain, &d);
    CHECK(status == 3); /* fmi2Error from the FMU */
    CHECK(strcmp(ssx_fmu_last_call(fmu), "fmi2SetReal") == 0);
    CHECK(d.k_seen == 0.0); /* the callback never ran */

    d.fail = 1;
    CHECK(ssx_fmu_initialize(fmu, &experiment, NULL, double_the_gain, &d) == -1);
    CHECK(d.k_seen == 1.0); /* it ran, with the model's own k, and failed */
    CHECK(ssx_fmu_is_instantiated(fmu)); /* never left initialization mode */
    ssx_fmu_free(fmu);
}

static void names_statuses(void)
{
    const char *expected[] = {"OK", "Warning", "Discard", "Error", "Fatal", "Pending"};
    for (int status = 0; status < 6; ++status) {
        CHECK(strcmp(ssx_status_name(status), expected[status]) == 0);
    }
    CHECK(strcmp(ssx_status_name(-1), "failed") == 0);
    CHECK(ssx_status_name(6) == NULL && ssx_status_name(-2) == NULL);
}

int main(void)
{
    writes_starts_then_calls_back();
    stops_at_the_failing_call();
    names_statuses();
    return 0;
}
