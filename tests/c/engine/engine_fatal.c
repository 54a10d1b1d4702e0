/* After fmi2Fatal the engine makes no further call on the FMU (FMI 2.0 forbids them all, even
 * fmi2FreeInstance): each later use is refused with a message naming the fatal call, and freeing
 * abandons the instance. The failing FMU logs any call it receives in its fatal state, so a call
 * that reached it would replace the engine's message. Its abandoned memory is the expected leak
 * (suppressed for LeakSanitizer in meson.build). */
#include <math.h>
#include <string.h>

#include "test_support.h"

enum { FAILING_Y = 0, FAILING_TIME = 2, FAILING_MODE = 3 };

static void check_refused(ssx_fmu *fmu, int status, const char *call)
{
    char expected[160];
    snprintf(expected, sizeof expected,
             "%s refused: fmi2DoStep returned fmi2Fatal earlier, and FMI 2.0 allows no further "
             "call on the FMU",
             call);
    if (status != -1 || strcmp(ssx_fmu_last_message(fmu), expected) != 0) {
        fprintf(stderr, "%s: status %d, message \"%s\"\n", call, status,
                ssx_fmu_last_message(fmu));
        exit(1);
    }
}

int main(void)
{
    ssx_fmu *fmu = load_fmu("failing");
    const int fatal = 1;
    const unsigned int time_vr = FAILING_TIME, mode_vr = FAILING_MODE;
    const double fail_time = 0.5;
    const ssx_fmu_experiment experiment = {.start_time = 0.0};
    const ssx_fmu_values starts = {.real_vr = &time_vr, .real_values = &fail_time, .n_real = 1,
                                   .integer_vr = &mode_vr, .integer_values = &fatal,
                                   .n_integer = 1};
    CHECK(ssx_fmu_initialize(fmu, &experiment, &starts, NULL, NULL) == 0);
    void *state = NULL;
    CHECK(ssx_fmu_get_state(fmu, &state) == 0);

    ssx_system *sys = ssx_system_new("fatal");
    int c = ssx_add_fmu_component(sys, "broken", fmu, 1);
    CHECK(ssx_add_output(sys, c, SSX_REAL, FAILING_Y) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_run(sys, 0.0, 1.0, 0.1) == -1);
    puts(ssx_last_error(sys)->message);
    CHECK(ssx_last_error(sys)->fmi_status == 4);
    CHECK(strstr(ssx_last_error(sys)->message,
                 "component 'broken': fmi2DoStep failed at t=0.5 with status fmi2Fatal (FMU log: "
                 "fmi2DoStep from t = 0.5") != NULL);
    CHECK(ssx_fmu_is_dead(fmu));

    double y = 0.0;
    check_refused(fmu, ssx_fmu_get_real(fmu, (const unsigned int[]){FAILING_Y}, 1, &y),
                  "fmi2GetReal");
    check_refused(fmu, ssx_fmu_set_state(fmu, state), "fmi2SetFMUstate");
    check_refused(fmu, ssx_fmu_terminate(fmu), "fmi2Terminate");
    check_refused(fmu, ssx_fmu_reset(fmu), "fmi2Reset");
    check_refused(fmu, ssx_fmu_instantiate(fmu), "fmi2Instantiate");
    CHECK(ssx_run(sys, 0.5, 1.0, 0.1) == -1); /* the system steps it no more either */
    check_refused(fmu, -1, "fmi2DoStep");
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(fmu, &counters);
    CHECK(counters.do_step == 6 && counters.instantiate == 1);

    CHECK(ssx_fmu_free_state(fmu, &state) == 0 && state == NULL);
    CHECK(ssx_fmu_free_instance(fmu) == 0);
    CHECK(!ssx_fmu_is_instantiated(fmu));
    check_refused(fmu, -1, "fmi2DoStep"); /* neither call reached the FMU: no message of its own */
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
    puts("engine fatal: ok");
    return 0;
}
