/* Initialization and the time loop over the communication grid t0 + k*dt. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "algorithm.h"
#include "component.h"
#include "component_calls.h"
#include "coupling.h"
#include "error.h"
#include "event_source.h"
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

static void grid_start(execution_grid *g, double origin, double dt)
{
    *g = (execution_grid){.origin = origin, .dt = dt, .next = 1};
}

int ssx_set_allow_non_finite(ssx_system *sys, int allow)
{
    sys->allow_non_finite = allow != 0;
    return 0;
}

int ssx_set_stop_at_own_events(ssx_system *sys, int stop)
{
    sys->stop_at_own_events = stop != 0;
    return 0;
}

/* Every component can save and restore its state. */
static int all_can_roll_back(const ssx_system *sys)
{
    for (int i = 0; i < sys->n_components; ++i) {
        if (!component_can_roll_back(sys->components[i])) {
            return 0;
        }
    }
    return 1;
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
    /* a system that locates its output clocks' ticks rolls back as one with indicators does */
    sys->own_event_stops = sys->stop_at_own_events && all_can_roll_back(sys);
    sys->stepping_hybrid =
        system_is_hybrid(sys) || event_sources_locate_ticks(sys) || sys->own_event_stops;
    grid_start(&sys->grid, t0, 0.0);
    if (check_components(sys) != 0 || coupling_prepare(sys) != 0 ||
        input_order_prepare(sys) != 0 || master_algorithm_choose(sys) != 0) {
        return -1;
    }
    finite_outputs_watch(sys);
    indicators_watch_outputs(sys);
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

/* The end of the communication step that starts at grid point next - 1 (or inside its
 * interval), for a stretch that ends at t_stop: the grid point, or t_stop for the step that
 * would cross it; a remainder below 1e-9 steps joins that step instead of making a sliver. */
static double step_end_before(const execution_grid *g, double t_stop)
{
    double last = ceil((t_stop - g->origin) / g->dt - 1e-9);
    return (double)g->next >= last ? t_stop : g->origin + (double)g->next * g->dt;
}

/* The step under way is complete at its end: the grid points it reached (within the joining
 * remainder) are behind. */
static void step_completed(execution_grid *g)
{
    g->in_step = 0;
    while (g->origin + (double)g->next * g->dt <= g->step_end + 1e-9 * g->dt) {
        g->next++;
    }
}

/* Steps towards t_stop until it is reached, or right after the first event instant located
 * and handled (*event set), or a member's own event where the system stops at those. A
 * request to end the simulation is the end, not a failure. */
static int advance(ssx_system *sys, double t_stop, int *event)
{
    execution_grid *g = &sys->grid;
    *event = 0;
    while (sys->time < t_stop) {
        long own_before = sys->stats.own_events;
        if (!g->in_step) {
            g->step_start = sys->time;
            g->step_end = step_end_before(g, t_stop);
            g->in_step = 1;
        } else if (g->step_end > t_stop) {
            g->step_end = t_stop;
        }
        int status = sys->algorithm->step(sys, g->step_start, sys->time, g->step_end, event);
        if (sys->termination.component >= 0) {
            /* sys->time is the last point the whole system completed */
            *event = 0;
            clear_error(sys);
            return 0;
        }
        if (status != 0) {
            return -1;
        }
        if (sys->time >= g->step_end) {
            step_completed(g);
            if (run_interrupted(sys, g->step_end) != 0) {
                return -1;
            }
        }
        /* an own event at the step's end (not cut there) ends the stretch there too */
        if (*event || (sys->own_event_stops && sys->stats.own_events > own_before)) {
            *event = 1;
            return 0;
        }
    }
    return 0;
}

/* What ssx_run and ssx_step_until refuse alike. */
static int check_can_go_on(ssx_system *sys, double t)
{
    if (!sys->initialized) {
        return fail_config(sys, -1, -1, t,
                           "system '%s' is not initialized (call ssx_initialize after changing it)",
                           sys->name);
    }
    if (sys->termination.component >= 0) {
        return fail_kind(sys, SSX_ERROR_TERMINATED, sys->termination.component, -1, t,
                         "system '%s' ended at t=%.17g: component '%s' asked to stop at t=%.17g; "
                         "initialize the system again to start a new run",
                         sys->name, sys->time, sys->components[sys->termination.component]->name,
                         sys->termination.time);
    }
    return 0;
}

static int check_step(ssx_system *sys, double t0, double dt)
{
    if (!(dt > 0.0)) {
        return fail_config(sys, -1, -1, t0, "system '%s': the step dt must be positive (got %g)",
                           sys->name, dt);
    }
    return 0;
}

/* Steps from t0 to tf would not fit the history's size arithmetic. */
static int check_step_count(ssx_system *sys, double t0, double tf, double dt)
{
    double ratio = (tf - t0) / dt;
    if (ratio > SSX_MAX_GRID_STEPS) {
        return fail_config(sys, -1, -1, t0, "system '%s': %.3g steps of dt=%g are too many",
                           sys->name, ratio, dt);
    }
    return 0;
}

/* The communication steps from t0 to tf (the recording sizes its buffers by them). */
static long step_count(double t0, double tf, double dt)
{
    long n_steps = tf > t0 ? (long)ceil((tf - t0) / dt - 1e-9) : 0;
    return n_steps < 1 && tf > t0 ? 1 : n_steps;
}

/* One stretch of stepping to t_stop between the recording's run start and end, the isolated
 * FMUs watched by the monitor meanwhile. */
static int run_stretch(ssx_system *sys, double t_stop, long n_steps, int stop_at_event,
                       int *event)
{
    if (recording_run_start(sys, (size_t)n_steps, t_stop) != 0) {
        return -1;
    }
    watch_isolated_fmus(sys, stop_requested_by_monitor);
    monitor_start(&sys->monitor);
    int status = 0;
    *event = 0;
    while (status == 0 && sys->time < t_stop && sys->termination.component < 0 &&
           !(stop_at_event && *event)) {
        status = advance(sys, t_stop, event);
    }
    monitor_stop(&sys->monitor);
    watch_isolated_fmus(sys, NULL);
    recording_run_end(sys);
    return status;
}

int ssx_run(ssx_system *sys, double t0, double tf, double dt)
{
    clear_error(sys);
    if (check_can_go_on(sys, t0) != 0) {
        return -1;
    }
    if (!isfinite(t0) || !isfinite(tf) || !isfinite(dt)) {
        return fail_config(sys, -1, -1, t0,
                           "system '%s': t0, tf and dt must be finite (got %g, %g, %g)", sys->name,
                           t0, tf, dt);
    }
    if (check_step(sys, t0, dt) != 0) {
        return -1;
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
    if (check_step_count(sys, t0, tf, dt) != 0) {
        return -1;
    }
    /* the run's grid is its own, from its t0 */
    grid_start(&sys->grid, t0, dt);
    if (tf > t0) {
        sys->time = t0;
    }
    int event;
    return run_stretch(sys, tf, step_count(t0, tf, dt), 0, &event);
}

int ssx_step_until(ssx_system *sys, double t_stop, double dt, ssx_step_outcome *out)
{
    clear_error(sys);
    int event = 0;
    long own_before = sys->stats.own_events;
    int status = check_can_go_on(sys, t_stop);
    if (status == 0 && (!isfinite(t_stop) || !isfinite(dt))) {
        status = fail_config(sys, -1, -1, t_stop,
                             "system '%s': t_stop and dt must be finite (got %g, %g)", sys->name,
                             t_stop, dt);
    }
    if (status == 0) {
        status = check_step(sys, sys->time, dt);
    }
    if (status == 0 && t_stop < sys->time) {
        status = fail_config(sys, -1, -1, t_stop, "system '%s' is at t=%.17g, past t_stop=%.17g",
                             sys->name, sys->time, t_stop);
    }
    if (status == 0) {
        status = check_step_count(sys, sys->time, t_stop, dt);
    }
    if (status == 0) {
        execution_grid *g = &sys->grid;
        if (g->dt == 0.0) {
            g->dt = dt; /* the grid from ssx_initialize's time */
        } else if (g->dt != dt) {
            grid_start(g, sys->time, dt);
        }
        status = run_stretch(sys, t_stop, step_count(sys->time, t_stop, dt), 1, &event);
    }
    if (out != NULL) {
        *out = (ssx_step_outcome){.time = sys->time,
                                  .event = event,
                                  .own_event = event && sys->own_event_stops &&
                                               sys->stats.own_events > own_before,
                                  .events = sys->stats.events,
                                  .status = status,
                                  .terminated = sys->termination.component >= 0};
    }
    return status;
}
