/* FMU initialization as one call: the sequence every user of an FMU repeats (the Python
 * component, the engine's tests), written once; or all of it but leaving initialization mode,
 * which a system does once the connected inputs are given (ssx_initialize). */
#include <stddef.h>

#include "syssimx_engine.h"

/* Keeps the highest status of the sequence; a failing one (above Warning, or -1) ends it. */
static int went_on(int status, int *highest)
{
    if (status < 0 || status > 1) {
        *highest = status;
        return 0;
    }
    *highest = status > *highest ? status : *highest;
    return 1;
}

static int write_starts(ssx_fmu *fmu, const ssx_fmu_values *v, int *highest)
{
    return (v->n_real == 0 ||
            went_on(ssx_fmu_set_real(fmu, v->real_vr, v->n_real, v->real_values), highest)) &&
           (v->n_integer == 0 ||
            went_on(ssx_fmu_set_integer(fmu, v->integer_vr, v->n_integer, v->integer_values),
                    highest)) &&
           (v->n_boolean == 0 ||
            went_on(ssx_fmu_set_boolean(fmu, v->boolean_vr, v->n_boolean, v->boolean_values),
                    highest));
}

/* A live instance is reset rather than instantiated again: the FMU keeps its allocations (a
 * CVODE integrator's memory, its FMU states) and the call costs a fraction of an instantiation.
 * An instance that refuses the reset (a broken one, or one in a state that forbids it) is
 * replaced. */
static int start_instance(ssx_fmu *fmu)
{
    if (ssx_fmu_is_instantiated(fmu) && !ssx_fmu_is_dead(fmu)) {
        int status = ssx_fmu_reset(fmu);
        if (status == 0 || status == 1) {
            return status;
        }
    }
    return ssx_fmu_instantiate(fmu);
}

int ssx_fmu_enter_initialization(ssx_fmu *fmu, const ssx_fmu_experiment *experiment,
                                 const ssx_fmu_values *starts,
                                 int (*in_initialization_mode)(void *user), void *user)
{
    if (fmu == NULL || experiment == NULL) {
        return -1;
    }
    const ssx_fmu_experiment *e = experiment;
    int highest = 0;
    /* each call only while the ones before it went on */
    (void)(went_on(start_instance(fmu), &highest) &&
           went_on(ssx_fmu_setup_experiment(fmu, e->tolerance_defined, e->tolerance,
                                            e->start_time, e->stop_time_defined, e->stop_time),
                   &highest) &&
           went_on(ssx_fmu_enter_initialization_mode(fmu), &highest) &&
           (starts == NULL || write_starts(fmu, starts, &highest)) &&
           (in_initialization_mode == NULL ||
            went_on(in_initialization_mode(user) == 0 ? 0 : -1, &highest)));
    return highest;
}

int ssx_fmu_initialize(ssx_fmu *fmu, const ssx_fmu_experiment *experiment,
                       const ssx_fmu_values *starts, int (*in_initialization_mode)(void *user),
                       void *user)
{
    int highest = ssx_fmu_enter_initialization(fmu, experiment, starts, in_initialization_mode,
                                               user);
    if (highest == 0 || highest == 1) {
        (void)went_on(ssx_fmu_exit_initialization_mode(fmu), &highest);
    }
    return highest;
}
