/* Initialization and the time loop over the communication grid t0 + k*dt. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "algorithm.h"
#include "component.h"
#include "component_calls.h"
#include "coupling.h"
#include "error.h"
#include "finite_outputs.h"
#include "fmu_binding.h"
#include "fmu_component.h"
#include "fmu_remote.h"
#include "indicator.h"
#include "input_order.h"
#include "interrupt.h"
#include "own_events.h"
#include "recording.h"
#include "system.h"

/* Steps beyond this would not fit the history's size arithmetic. */
#define SSX_MAX_GRID_STEPS 1e12

static int check_components(ssx_system *sys)
{
    int hybrid = system_is_hybrid(sys);
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        if (c->ops->validate != NULL && c->ops->validate(sys, c) != 0) {
            return -1;
        }
        if (hybrid && !component_can_roll_back(c)) {
            return fail(sys, i, -1, sys->time,
                        "component '%s' cannot save and restore its state, but the system has "
                        "event indicators: locating an event restores every component",
                        c->name);
        }
        /* a rejected step is taken again from the state saved at its start: never ask an FMU
         * for a state it does not declare it can give */
        if (sys->step_control.enabled && sys->step_control.rollback &&
            !component_can_roll_back(c)) {
            return fail_config(sys, i, -1, sys->time,
                               "component '%s' cannot save and restore its state (its FMU does "
                               "not declare canGetAndSetFMUstate), but the step control rejects "
                               "steps by rolling back: use a step control with rollback off",
                               c->name);
        }
    }
    return 0;
}

int ssx_set_allow_non_finite(ssx_system *sys, int allow)
{
    sys->allow_non_finite = allow != 0;
    return 0;
}

int ssx_initialize(ssx_system *sys, double t0)
{
    clear_error(sys);
    sys->initialized = 0;
    if (!isfinite(t0)) {
        return fail_config(sys, -1, -1, t0, "system '%s': the start time must be finite",
                           sys->name);
    }
    sys->time = t0;
    sys->termination.component = -1;
    memset(&sys->stats, 0, sizeof sys->stats);
    localization_log_clear(&sys->localization);
    own_events_clear(sys);
    sys->stepping_hybrid = system_is_hybrid(sys);
    if (check_components(sys) != 0 || coupling_prepare(sys) != 0 ||
        input_order_prepare(sys) != 0 || master_algorithm_choose(sys) != 0) {
        return -1;
    }
    finite_outputs_watch(sys);
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        for (int k = 0; k < c->n_inputs; ++k) {
            if (c->input_driver[k] < 0) {
                c->inputs[k] = c->input_starts[k];
            }
        }
    }
    if (coupling_initialize(sys, t0) != 0 || recording_start(sys) != 0 ||
        indicators_evaluate(sys, t0) != 0) {
        return -1;
    }
    indicators_start(sys);
    if (record_grid_point(sys, t0) != 0) {
        return -1;
    }
    sys->initialized = 1;
    return 0;
}

/* An isolated FMU's call waits on its host's socket: the monitor (Ctrl-C, the run's timeout)
 * is asked while it waits, as between steps. */
static int stop_requested_by_monitor(void *user)
{
    ssx_system *sys = user;
    return sys->monitor.call != NULL ? sys->monitor.call(sys->monitor.user, sys->time) : 0;
}

static void watch_isolated_fmus(ssx_system *sys, int (*stop)(void *user))
{
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_fmu *fmu = fmu_component_binding(sys->components[i]);
        if (fmu != NULL) {
            ssx_remote_set_watch(ssx_fmu_remote(fmu), stop, sys);
        }
    }
}

static int run_grid(ssx_system *sys, double t0, double tf, double dt, long n_steps)
{
    double t = t0;
    monitor_start(&sys->monitor);
    for (long k = 1; k <= n_steps; ++k) {
        double t_next = k == n_steps ? tf : t0 + (double)k * dt;
        int status = sys->algorithm->step(sys, t, t_next);
        if (sys->termination.component >= 0) {
            /* the end, not a failure: sys->time is the last point the whole system completed */
            clear_error(sys);
            return 0;
        }
        if (status != 0) {
            return -1;
        }
        t = t_next;
        if (run_interrupted(sys, t) != 0) {
            return -1;
        }
    }
    sys->time = tf > t0 ? tf : sys->time;
    return 0;
}

int ssx_run(ssx_system *sys, double t0, double tf, double dt)
{
    clear_error(sys);
    if (!sys->initialized) {
        return fail_config(sys, -1, -1, t0,
                           "system '%s' is not initialized (call ssx_initialize after changing it)",
                           sys->name);
    }
    if (sys->termination.component >= 0) {
        return fail_kind(sys, SSX_ERROR_TERMINATED, sys->termination.component, -1, t0,
                         "system '%s' ended at t=%.17g: component '%s' asked to stop at t=%.17g; "
                         "initialize the system again to start a new run",
                         sys->name, sys->time, sys->components[sys->termination.component]->name,
                         sys->termination.time);
    }
    if (!isfinite(t0) || !isfinite(tf) || !isfinite(dt)) {
        return fail_config(sys, -1, -1, t0,
                           "system '%s': t0, tf and dt must be finite (got %g, %g, %g)", sys->name,
                           t0, tf, dt);
    }
    if (!(dt > 0.0)) {
        return fail_config(sys, -1, -1, t0, "system '%s': the step dt must be positive (got %g)",
                           sys->name, dt);
    }
    if (tf < t0) {
        return fail_config(sys, -1, -1, t0, "system '%s': tf=%.17g lies before t0=%.17g", sys->name,
                           tf, t0);
    }
    if (fabs(t0 - sys->time) > 1e-12 * fmax(1.0, fabs(t0))) {
        return fail_config(sys, -1, -1, t0,
                           "system '%s' is at t=%.17g; a run must start there, not at "
                           "t0=%.17g",
                           sys->name, sys->time, t0);
    }
    double ratio = (tf - t0) / dt;
    if (ratio > SSX_MAX_GRID_STEPS) {
        return fail_config(sys, -1, -1, t0, "system '%s': %.3g steps of dt=%g are too many",
                           sys->name, ratio, dt);
    }
    /* A remainder below 1e-9 steps joins the last step instead of making a sliver step. */
    long n_steps = tf > t0 ? (long)ceil(ratio - 1e-9) : 0;
    if (n_steps < 1 && tf > t0) {
        n_steps = 1;
    }
    if (recording_run_start(sys, (size_t)n_steps, tf) != 0) {
        return -1;
    }
    watch_isolated_fmus(sys, stop_requested_by_monitor);
    int status = run_grid(sys, t0, tf, dt, n_steps);
    monitor_stop(&sys->monitor);
    watch_isolated_fmus(sys, NULL);
    recording_run_end(sys);
    return status;
}
