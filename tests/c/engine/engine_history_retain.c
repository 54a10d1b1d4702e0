/* A retained history keeps its samples through later runs, a new initialize and the system's
 * free (run under AddressSanitizer too); a monitor stops a run between macro steps. */
#include <math.h>
#include <string.h>

#include "test_support.h"

static ssx_system *pendulum_system(ssx_fmu *fmu)
{
    CHECK(start_pendulum(fmu, 0.0, 0.5, 0.0, 0.0) == 0);
    ssx_system *sys = ssx_system_new("retain");
    CHECK(add_pendulum(sys, "pendulum", fmu) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    return sys;
}

/* The samples a reader got stay where they were, with their values. */
static void check_samples(const double *time, const double *values, const double *expected_time,
                          const double *expected_values, size_t n)
{
    CHECK(memcmp(time, expected_time, n * sizeof *time) == 0);
    CHECK(memcmp(values, expected_values, 3 * n * sizeof *values) == 0);
}

static void test_retained_samples_survive(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    ssx_system *sys = pendulum_system(fmu);
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.01));
    size_t n = ssx_history_length(sys);
    CHECK(n == 101);
    ssx_history_block *block = ssx_history_retain(sys);
    CHECK(block != NULL);
    const double *time = ssx_history_time(sys);
    const double *values = ssx_history_values(sys, 0);
    double expected_time[101], expected_values[3 * 101];
    memcpy(expected_time, time, sizeof expected_time);
    memcpy(expected_values, values, sizeof expected_values);

    /* the history outgrows the retained buffers: it continues in new ones */
    CHECK_OK(sys, ssx_run(sys, 1.0, 30.0, 0.01));
    CHECK(ssx_history_length(sys) == 3001);
    CHECK(ssx_history_time(sys) != time);
    CHECK(memcmp(ssx_history_time(sys), expected_time, sizeof expected_time) == 0);
    check_samples(time, values, expected_time, expected_values, n);

    ssx_history_block *second = ssx_history_retain(sys);
    const double *second_time = ssx_history_time(sys);
    CHECK(start_pendulum(fmu, 0.0, 0.25, 0.0, 0.0) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_history_length(sys) == 1 && ssx_history_values(sys, 0)[0] == 0.25);
    check_samples(time, values, expected_time, expected_values, n);
    CHECK(second_time[3000] == 30.0);

    ssx_system_free(sys);
    check_samples(time, values, expected_time, expected_values, n);
    CHECK(second_time[3000] == 30.0);
    ssx_history_release(second);
    ssx_history_release(block);
    ssx_fmu_free(fmu);
}

static void test_unretained_history_is_trimmed_to_its_samples(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    ssx_system *sys = pendulum_system(fmu);
    /* grown by doubling while it runs, given back down to the 1001 samples at the end */
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.001));
    CHECK(ssx_history_length(sys) == 1001);
    CHECK(ssx_history_bytes(sys) == 1001 * (8 + 4 + 3 * 8));
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* Python's `result = system.run(...)` in a loop: each run starts while the previous result
 * still holds the history. The engine copies it only when it outgrows its room, into twice
 * the samples, so 200 runs move it a handful of times, not 200. */
static void test_held_results_copy_rarely(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    ssx_system *sys = pendulum_system(fmu);
    ssx_history_block *held = ssx_history_retain(sys);
    const double *time = ssx_history_time(sys);
    int moves = 0;
    for (int k = 0; k < 200; ++k) {
        CHECK_OK(sys, ssx_run(sys, k * 0.05, (k + 1) * 0.05, 0.001));
        moves += ssx_history_time(sys) != time;
        time = ssx_history_time(sys);
        ssx_history_block *result = ssx_history_retain(sys);
        ssx_history_release(held);
        held = result;
    }
    CHECK(ssx_history_length(sys) == 10001 && time[10000] == 10.0);
    CHECK(moves >= 5 && moves <= 10); /* 51 -> 10001 samples by doubling: about log2(200) */
    ssx_history_release(held);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

typedef struct {
    int calls;
    double last_t;
} stop_on_second_call;

static int stop_on_second(void *user, double t)
{
    stop_on_second_call *state = user;
    state->calls++;
    state->last_t = t;
    return state->calls >= 2;
}

static void test_monitor_stops_the_run(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    ssx_system *sys = pendulum_system(fmu);
    stop_on_second_call state = {0, NAN};
    CHECK(ssx_set_monitor(sys, stop_on_second, &state) == 0);
    /* 10^9 steps: only the monitor ends this run in the test's time */
    CHECK(ssx_run(sys, 0.0, 1.0, 1e-9) == -1);
    const ssx_error *error = ssx_last_error(sys);
    CHECK(state.calls == 2);
    CHECK(error->kind == SSX_ERROR_CALLBACK && error->time == state.last_t);
    CHECK(strstr(error->message, "stopped by its monitor") != NULL);
    size_t n = ssx_history_length(sys);
    CHECK(ssx_time(sys) == state.last_t && ssx_history_time(sys)[n - 1] == state.last_t);
    /* not reserved for 10^9 samples of 36 bytes: the room ahead is given back at the stop */
    CHECK(ssx_history_bytes(sys) == n * (8 + 4 + 3 * 8));
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* ssx_get_run_outcome reads what each accessor reads, and its history reference keeps the
 * samples like ssx_history_retain's. */
static void test_run_outcome_is_the_accessors(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    ssx_system *sys = pendulum_system(fmu);
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.5, 0.05));
    ssx_run_outcome outcome;
    ssx_get_run_outcome(sys, &outcome);
    ssx_statistics statistics;
    ssx_get_statistics(sys, &statistics);
    CHECK(outcome.time == ssx_time(sys) && outcome.time == 0.5);
    CHECK(outcome.n_events == ssx_event_count(sys) && outcome.n_events == 0);
    CHECK(outcome.termination == ssx_get_termination(sys) &&
          outcome.termination->component == -1);
    CHECK(memcmp(&outcome.statistics, &statistics, sizeof statistics) == 0);
    CHECK(outcome.statistics.macro_steps == 10);
    CHECK(outcome.history_length == ssx_history_length(sys) && outcome.history_length == 11);
    CHECK(outcome.history_time == ssx_history_time(sys));
    CHECK(outcome.history_micro == ssx_history_micro(sys));
    CHECK(outcome.history != NULL &&
          ssx_history_block_values(outcome.history, 0) == ssx_history_values(sys, 0));
    double last = outcome.history_time[10];
    CHECK(start_pendulum(fmu, 0.0, 0.25, 0.0, 0.0) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    ssx_system_free(sys);
    CHECK(outcome.history_time[10] == last && last == 0.5); /* held by the reference */
    ssx_history_release(outcome.history);
    ssx_fmu_free(fmu);
}

int main(void)
{
    test_run_outcome_is_the_accessors();
    test_retained_samples_survive();
    test_unretained_history_is_trimmed_to_its_samples();
    test_held_results_copy_rarely();
    test_monitor_stops_the_run();
    return 0;
}
