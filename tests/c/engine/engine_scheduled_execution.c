/* FMI 3.0 Scheduled Execution in the FMU binding: the hand-written FMU of
 * tests/fmus/fmi3_scheduled loaded as SSX_SCHEDULED_EXECUTION, its partitions activated one by
 * one. Its clockUpdate callbacks announce the countdown clock `later` after each odd tick of
 * `tick` (0.25 s on) and the output clock `alarm` at every third; the engine reads both inside
 * the callback and hands them out once. The misbehaving builds unbalance the preemption lock or
 * fail in a partition: each activation that does fails, naming why.
 *
 * Arguments: the binaries of fmi3_scheduled, fmi3_scheduled_unbalanced, fmi3_scheduled_failing.
 * Not under test_support.h: it needs none of the models' FMUs. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "syssimx_engine.h"

static int failures;

#define CHECK(condition) do { \
    if (!(condition)) { \
        fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition); \
        ++failures; \
    } \
} while (0)

/* tests/fmus/fmi3_scheduled/modelDescription.xml */
enum { TICK = 1, LATER = 2, ALARM = 3, COUNT = 4, LATER_COUNT = 5, GAIN = 6, SUM = 7 };

static const unsigned int port_vr[] = {COUNT, LATER_COUNT, GAIN, SUM};
static const unsigned char port_types[] = {SSX_FMI3_INT32, SSX_FMI3_INT32, SSX_FMI3_FLOAT64,
                                           SSX_FMI3_FLOAT64};
static const char *const port_names[] = {"count", "laterCount", "gain", "sum"};
static const unsigned int output_clocks[] = {ALARM};
static const unsigned int countdown_clocks[] = {LATER};
static const ssx_fmi3_variables variables = {
    .vr = port_vr, .type = port_types, .name = port_names, .n = 4,
    .output_clock_vr = output_clocks, .n_output_clocks = 1,
    .countdown_clock_vr = countdown_clocks, .n_countdown_clocks = 1};

/* The FMU in Clock Activation Mode at 0, NULL (said why) when it cannot be. */
static ssx_fmu *started(const char *binary)
{
    ssx_fmu_load_spec spec = {.version = SSX_FMI3, .interface = SSX_SCHEDULED_EXECUTION,
                              .binary_path = binary, .model_identifier = "fmi3_scheduled",
                              .guid = "{3b0d6a52-6f0e-4c47-9d0c-2d2f1f8a7e11}",
                              .instance_name = "scheduled", .fmi3_variables = &variables};
    char error[512];
    ssx_fmu *fmu = ssx_fmu_load(&spec, error, sizeof error);
    if (fmu == NULL) {
        fprintf(stderr, "loading %s: %s\n", binary, error);
        ++failures;
        return NULL;
    }
    CHECK(ssx_fmu_instantiate(fmu) == 0);
    CHECK(ssx_fmu_setup_experiment(fmu, 0, 0.0, 0.0, 0, 0.0) == 0);
    CHECK(ssx_fmu_enter_initialization_mode(fmu) == 0);
    CHECK(ssx_fmu_exit_initialization_mode(fmu) == 0);
    return fmu;
}

static void partitions_and_their_updates(const char *binary)
{
    ssx_fmu *fmu = started(binary);
    if (fmu == NULL) {
        return;
    }
    int ticked = -1;
    double next = 0.0;
    CHECK(ssx_fmu_activate_model_partition(fmu, TICK, 0.0) == 0); /* count 1: later announced */
    ssx_fmu_take_clock_updates(fmu, &ticked, &next);
    CHECK(ticked == 0 && next == 0.25);
    ssx_fmu_take_clock_updates(fmu, &ticked, &next); /* taken once */
    CHECK(ticked == 0 && isinf(next));
    CHECK(ssx_fmu_activate_model_partition(fmu, TICK, 0.5) == 0); /* count 2: nothing */
    ssx_fmu_take_clock_updates(fmu, &ticked, &next);
    CHECK(ticked == 0 && isinf(next));
    const unsigned int gain = GAIN;
    const double two = 2.0;
    CHECK(ssx_fmu_set_real(fmu, &gain, 1, &two) == 0);
    CHECK(ssx_fmu_activate_model_partition(fmu, TICK, 1.0) == 0); /* count 3: both */
    ssx_fmu_take_clock_updates(fmu, &ticked, &next);
    CHECK(ticked == 1 && next == 1.25);
    CHECK(ssx_fmu_activate_model_partition(fmu, LATER, 1.25) == 0);
    const unsigned int counts_vr[] = {COUNT, LATER_COUNT};
    int counts[2] = {0, 0};
    CHECK(ssx_fmu_get_integer(fmu, counts_vr, 2, counts) == 0);
    CHECK(counts[0] == 3 && counts[1] == 1);
    const unsigned int sum_vr = SUM;
    double sum = 0.0;
    CHECK(ssx_fmu_get_real(fmu, &sum_vr, 1, &sum) == 0);
    CHECK(sum == 2.0); /* gains 0 (the instance's own, never set), 0, 2 */
    CHECK(ssx_fmu_activate_model_partition(fmu, ALARM, 2.0) != 0); /* not an input clock */
    ssx_fmu_free(fmu);
}

/* The FMU as a component of a system run 0 .. 4 s by 1 s (on `threads` threads, with a second
 * system's component beside it when two): the tick clock every 0.5 s, then every 1 s from its
 * second tick (the FMU's interval), `later` 0.25 s after each odd tick, `alarm` with every
 * third tick; the ticks logged with what they moved, the ports holding the last values. */
static void a_component_runs_the_ticks(const char *binary, int threads)
{
    ssx_fmu *fmu = NULL, *twin = NULL;
    ssx_fmu_load_spec spec = {.version = SSX_FMI3, .interface = SSX_SCHEDULED_EXECUTION,
                              .binary_path = binary, .model_identifier = "fmi3_scheduled",
                              .guid = "{3b0d6a52-6f0e-4c47-9d0c-2d2f1f8a7e11}",
                              .fmi3_variables = &variables};
    char error[512];
    ssx_system *sys = ssx_system_new("scheduled");
    int components[2] = {-1, -1};
    for (int k = 0; k < threads; ++k) {
        spec.instance_name = k == 0 ? "S" : "T";
        ssx_fmu **slot = k == 0 ? &fmu : &twin;
        *slot = ssx_fmu_load(&spec, error, sizeof error);
        CHECK(*slot != NULL);
        if (*slot == NULL) {
            ssx_system_free(sys);
            ssx_fmu_free(fmu);
            return;
        }
        int c = components[k] = ssx_add_scheduled_component(sys, spec.instance_name, *slot);
        CHECK(c == k);
        CHECK(ssx_add_output(sys, c, SSX_INTEGER, COUNT) == 0);
        CHECK(ssx_add_output(sys, c, SSX_INTEGER, LATER_COUNT) == 1);
        CHECK(ssx_add_output(sys, c, SSX_REAL, SUM) == 2);
        CHECK(ssx_add_input(sys, c, SSX_REAL, GAIN, 2.0) == 0);
        int tick = ssx_add_scheduled_clock(sys, c, SSX_SCHEDULED_PERIODIC, TICK, 1, NAN, 0.0, 1);
        int later = ssx_add_scheduled_clock(sys, c, SSX_SCHEDULED_COUNTDOWN, LATER, 0, NAN, 0.0,
                                            0);
        CHECK(ssx_add_scheduled_clock(sys, c, SSX_SCHEDULED_OUTPUT, ALARM, -1, NAN, 0.0, 0) == 2);
        CHECK(tick == 0 && later == 1);
        CHECK(ssx_add_scheduled_clock_output(sys, c, tick, 0) == 0);
        CHECK(ssx_add_scheduled_clock_output(sys, c, tick, 2) == 0);
        CHECK(ssx_add_scheduled_clock_output(sys, c, later, 1) == 0);
        ssx_fmu_experiment experiment = {.start_time = 0.0};
        CHECK(ssx_fmu_enter_initialization(*slot, &experiment, NULL, NULL, NULL) == 0);
    }
    CHECK(ssx_set_threads(sys, threads) == 0);
    CHECK(ssx_initialize(sys, 0.0) == 0);
    CHECK(ssx_run(sys, 0.0, 4.0, 1.0) == 0);
    if (ssx_last_error(sys)->message[0] != '\0') {
        fprintf(stderr, "%s\n", ssx_last_error(sys)->message);
    }
    static const double expected_time[] = {0.0, 0.25, 0.5, 1.5, 1.5, 1.75, 2.5, 3.5, 3.75};
    static const int expected_clock[] = {0, 1, 0, 0, 2, 1, 0, 0, 1};
    enum { N_TICKS = 9, N_VALUES = 13 };
    for (int k = 0; k < threads; ++k) {
        size_t n_values = 0;
        CHECK(ssx_scheduled_tick_count(sys, components[k], &n_values) == N_TICKS);
        CHECK(n_values == N_VALUES); /* count and sum at 5 ticks, laterCount at 3 */
        double time[N_TICKS], value[N_VALUES];
        int clock[N_TICKS], output[N_VALUES];
        size_t first[N_TICKS + 1];
        CHECK(ssx_scheduled_ticks(sys, components[k], time, clock, first, output, value) == 0);
        int counts[3] = {0, 0, 0};
        for (int i = 0; i < N_TICKS; ++i) {
            CHECK(time[i] == expected_time[i] && clock[i] == expected_clock[i]);
            ++counts[clock[i]];
            if (clock[i] == 0) {
                CHECK(first[i + 1] - first[i] == 2 && output[first[i]] == 0);
                CHECK(value[first[i]] == counts[0] && value[first[i] + 1] == 2.0 * counts[0]);
            } else if (clock[i] == 1) {
                CHECK(first[i + 1] - first[i] == 1 && output[first[i]] == 1);
                CHECK(value[first[i]] == counts[1]);
            } else {
                CHECK(first[i + 1] == first[i]);
            }
        }
    }
    /* the alarm is an own event of its component, output clock 1 */
    size_t alarms = 0;
    for (size_t i = 0; i < ssx_event_count(sys); ++i) {
        ssx_event_record event;
        CHECK(ssx_event_get(sys, i, &event) == 0);
        if (event.own == SSX_OWN_OUTPUT_CLOCK && event.clock == 1) {
            CHECK(event.t == 1.5);
            ++alarms;
        }
    }
    CHECK(alarms == (size_t)threads);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
    ssx_fmu_free(twin);
}

static void an_unbalanced_lock_fails_the_partition(const char *binary)
{
    ssx_fmu *fmu = started(binary);
    if (fmu == NULL) {
        return;
    }
    CHECK(ssx_fmu_activate_model_partition(fmu, TICK, 0.0) != 0);
    CHECK(strstr(ssx_fmu_last_message(fmu), "unlocked preemption it had not locked") != NULL);
    ssx_fmu_free(fmu);
}

static void a_failing_partition_fails_its_activation(const char *binary)
{
    ssx_fmu *fmu = started(binary);
    if (fmu == NULL) {
        return;
    }
    CHECK(ssx_fmu_activate_model_partition(fmu, TICK, 0.5) == 0);
    CHECK(ssx_fmu_activate_model_partition(fmu, TICK, 1.0) != 0);
    CHECK(strcmp(ssx_fmu_last_call(fmu), "fmi3ActivateModelPartition") == 0);
    ssx_fmu_free(fmu);
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s scheduled unbalanced failing\n", argv[0]);
        return 2;
    }
    partitions_and_their_updates(argv[1]);
    a_component_runs_the_ticks(argv[1], 1);
    a_component_runs_the_ticks(argv[1], 2);
    an_unbalanced_lock_fails_the_partition(argv[2]);
    a_failing_partition_fails_its_activation(argv[3]);
    if (failures == 0) {
        puts("ok");
    }
    return failures == 0 ? 0 : 1;
}
