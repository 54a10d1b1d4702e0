/* Building a system: components, ports, connections, indicators, event connections, schedule
 * and options. Its results are read in results.c. */
#define _POSIX_C_SOURCE 200809L

#include "system.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "algorithm.h"
#include "arena.h"
#include "array.h"
#include "component_calls.h"
#include "coupling.h"
#include "event_source.h"
#include "component_setup.h"
#include "error.h"
#include "indicator.h"
#include "input_order.h"
#include "locator.h"
#include "parallel_step.h"
#include "port_block.h"
#include "record_hooks.h"
#include "recording.h"

ssx_system *ssx_system_new(const char *name)
{
    ssx_system *sys = calloc(1, sizeof *sys);
    if (sys == NULL) {
        return NULL;
    }
    sys->name = strdup(name != NULL ? name : "system");
    if (sys->name == NULL) {
        free(sys);
        return NULL;
    }
    ssx_defaults d;
    ssx_get_defaults(&d);
    sys->coupling = d.coupling;
    sys->threads = d.threads;
    sys->loop = (ssx_loop_options){.tolerance = d.loop_tolerance,
                                   .max_iterations = d.loop_max_iterations,
                                   .damping = d.loop_damping,
                                   .jacobian = d.loop_jacobian};
    sys->hybrid = (ssx_hybrid_options){.tol_time = d.tol_time,
                                       .tol_value = d.tol_value,
                                       .max_iterations = d.max_iterations,
                                       .max_microsteps = d.max_microsteps,
                                       .record_internal_steps = 0,
                                       .locator = d.locator,
                                       .zeno_min_interval = d.zeno_min_interval};
    sys->input_order = d.input_order;
    sys->extrapolate_held_inputs = d.extrapolate_held_inputs;
    sys->step_control = (ssx_step_control){.enabled = 0,
                                           .rollback = 1,
                                           .rtol = d.step_rtol,
                                           .atol = d.step_atol,
                                           .min_step = d.step_min,
                                           .max_step = 0.0,
                                           .safety = d.step_safety,
                                           .min_change = d.step_min_change,
                                           .max_change = d.step_max_change,
                                           .energy = 0,
                                           .proportional_gain = d.step_proportional_gain,
                                           .integral_gain = d.step_integral_gain};
    sys->termination.component = -1;
    sys->recording = recording_new(d.output_interval);
    if (sys->recording == NULL) {
        free(sys->name);
        free(sys);
        return NULL;
    }
    clear_error(sys);
    return sys;
}

void ssx_system_free(ssx_system *sys)
{
    if (sys == NULL) {
        return;
    }
    input_order_free(sys); /* before the components whose inputs it moves */
    free(sys->power_bonds);
    for (int i = 0; i < sys->n_components; ++i) {
        component_free(sys->components[i]);
    }
    arena_free(&sys->component_blocks);
    arena_free(&sys->prepared_blocks);
    free(sys->components);
    free(sys->connections);
    free(sys->indicators);
    free(sys->indicator_states);
    master_algorithm_release(sys);
    event_sources_free(sys);
    port_block_free(sys); /* after the components that point into it */
    free(sys->order);
    free(sys->groups);
    recording_free(sys->recording);
    text_table_free(&sys->texts);
    parallel_free(sys->parallel);
    localization_log_free(&sys->localization);
    for (int i = 0; i < sys->n_owned_fmus; ++i) { /* after the components that borrow them */
        ssx_fmu_free(sys->owned_fmus[i]);
    }
    free(sys->owned_fmus);
    free(sys->name);
    free(sys);
}

const ssx_error *ssx_last_error(const ssx_system *sys)
{
    return sys != NULL ? &sys->error : NULL;
}

/* Any change of structure requires a new ssx_initialize. */
int ssx_add_python_component(ssx_system *sys, const char *name, int can_snapshot)
{
    return system_add_component(sys, name, can_snapshot, &ssx_python_component_ops, 0);
}

int ssx_set_hooks(ssx_system *sys, int component, const ssx_hooks *hooks)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (hooks == NULL) {
        memset(&c->hooks, 0, sizeof c->hooks);
    } else {
        c->hooks = *hooks;
    }
    c->has_step_hook = c->hooks.do_step != NULL;
    /* most systems have no record hook: no call for them on every sample */
    if (c->hooks.record != NULL && !sys->record_hooks_observed) {
        ssx_observer *observer = record_hooks_observer_new();
        if (observer == NULL || recording_add_sample_observer(sys->recording, observer) != 0) {
            return fail_config(sys, component, -1, sys->time,
                               "out of memory observing the record hooks");
        }
        sys->record_hooks_observed = 1;
    }
    system_structure_changed(sys);
    return 0;
}

int ssx_reset_inputs(ssx_system *sys, const double *starts, size_t n)
{
    size_t total = 0;
    for (int i = 0; i < sys->n_components; ++i) {
        total += (size_t)sys->components[i]->n_inputs;
    }
    if (total != n || (n > 0 && starts == NULL)) {
        return fail_config(sys, -1, -1, NAN,
                           "system '%s': %zu input start values given for %zu inputs", sys->name,
                           n, total);
    }
    /* checked whole before any is written: a refusal leaves every input as it was */
    const double *start = starts;
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        for (int k = 0; k < c->n_inputs; ++k, ++start) {
            if (isinf(*start) || (isnan(*start) && c->ops->adopt_inputs == NULL)) {
                return fail_config(sys, i, -1, NAN,
                                   "component '%s': the start value of input %d must be finite "
                                   "(NaN, the FMU's own value, exists for FMU components only)",
                                   c->name, k);
            }
        }
    }
    start = starts;
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        for (int k = 0; k < c->n_inputs; ++k, ++start) {
            c->inputs[k] = *start;
            c->input_starts[k] = *start;
        }
    }
    return 0;
}

double *ssx_outputs(ssx_system *sys, int component)
{
    ssx_component *c = system_component(sys, component);
    return c != NULL ? c->outputs : NULL;
}

double *ssx_inputs(ssx_system *sys, int component)
{
    ssx_component *c = system_component(sys, component);
    return c != NULL ? c->inputs : NULL;
}

int ssx_connect(ssx_system *sys, int src_component, int src_output, int dst_component,
                int dst_input, double scale, double offset)
{
    ssx_component *src = system_component(sys, src_component);
    ssx_component *dst = src != NULL ? system_component(sys, dst_component) : NULL;
    if (src == NULL || dst == NULL) {
        return -1;
    }
    if (src_output < 0 || src_output >= src->n_outputs) {
        return fail_config(sys, src_component, -1, NAN,
                           "component '%s' has no output %d (it has %d)", src->name, src_output,
                           src->n_outputs);
    }
    if (dst_input < 0 || dst_input >= dst->n_inputs) {
        return fail_config(sys, dst_component, -1, NAN,
                           "component '%s' has no input %d (it has %d)", dst->name, dst_input,
                           dst->n_inputs);
    }
    if (!isfinite(scale) || !isfinite(offset)) {
        return fail_config(sys, dst_component, -1, NAN,
                           "connection %s.out[%d] -> %s.in[%d]: scale and offset must be finite",
                           src->name, src_output, dst->name, dst_input);
    }
    ssx_value_type from = src->output_ports[src_output].type;
    ssx_value_type to = dst->input_ports[dst_input].type;
    int numbered = from >= SSX_STRING || to >= SSX_STRING; /* values are table numbers */
    if (numbered && (from != to || scale != 1.0 || offset != 0.0)) {
        return fail_config(sys, dst_component, -1, NAN,
                           "connection %s.out[%d] -> %s.in[%d]: a String or Binary port "
                           "connects to a port of its own type only, unscaled",
                           src->name, src_output, dst->name, dst_input);
    }
    int driver = dst->input_driver[dst_input];
    if (driver >= 0) {
        const ssx_connection *existing = &sys->connections[driver];
        return fail_config(sys, dst_component, -1, NAN,
                           "input %d of component '%s' is already driven by output %d of component "
                           "'%s': an input takes exactly one driver",
                           dst_input, dst->name, existing->src_output,
                           sys->components[existing->src_component]->name);
    }
    if (array_reserve((void **)&sys->connections, &sys->connections_capacity,
                      (size_t)sys->n_connections + 1, sizeof *sys->connections, 8) != 0) {
        return fail_config(sys, -1, -1, NAN, "out of memory adding a connection");
    }
    sys->connections[sys->n_connections] = (ssx_connection){
        .src_component = src_component,
        .src_output = src_output,
        .dst_component = dst_component,
        .dst_input = dst_input,
        .scale = scale,
        .offset = offset,
    };
    dst->input_driver[dst_input] = sys->n_connections++;
    system_structure_changed(sys);
    return 0;
}

static int add_indicator(ssx_system *sys, ssx_indicator indicator)
{
    if (indicator.direction < -1 || indicator.direction > 1) {
        return fail_config(sys, indicator.component, -1, NAN,
                           "component '%s': indicator direction must be -1, 0 or +1, not %d",
                           sys->components[indicator.component]->name, indicator.direction);
    }
    if (array_reserve((void **)&sys->indicators, &sys->indicators_capacity,
                      (size_t)sys->n_indicators + 1, sizeof *sys->indicators, 8) != 0) {
        return fail_config(sys, -1, -1, NAN, "out of memory adding an indicator");
    }
    sys->indicators[sys->n_indicators] = indicator;
    system_structure_changed(sys);
    return sys->n_indicators++;
}

int ssx_add_indicator_output(ssx_system *sys, int component, int output, int direction)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (output < 0 || output >= c->n_outputs) {
        return fail_config(sys, component, -1, NAN, "component '%s' has no output %d (it has %d)",
                           c->name, output, c->n_outputs);
    }
    return add_indicator(sys, (ssx_indicator){.component = component,
                                              .output = output,
                                              .direction = direction});
}

/* The indicator of that index, or NULL (with a configuration error where sys is there). */
static ssx_indicator *system_indicator(ssx_system *sys, int indicator)
{
    if (sys == NULL) {
        return NULL;
    }
    if (indicator < 0 || indicator >= sys->n_indicators) {
        fail_config(sys, -1, indicator, NAN, "no indicator %d (there are %d)", indicator,
                    sys->n_indicators);
        return NULL;
    }
    return &sys->indicators[indicator];
}

int ssx_set_indicator_slope(ssx_system *sys, int indicator, unsigned int vr)
{
    ssx_indicator *ind = system_indicator(sys, indicator);
    if (ind == NULL) {
        return -1;
    }
    const ssx_component *c = sys->components[ind->component];
    if (ind->output < 0 || c->ops->fmu == NULL) {
        return fail_config(sys, ind->component, indicator, NAN,
                           "component '%s': only an indicator on an output of an FMU "
                           "component can take its slope from the FMU",
                           c->name);
    }
    ind->has_slope = 1;
    ind->slope_vr = vr;
    return 0;
}

int ssx_add_indicator_callback(ssx_system *sys, int component,
                               int (*evaluate)(void *user, double t, double *value), void *user,
                               int direction)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (evaluate == NULL) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s': a callback indicator needs an "
                           "evaluate function",
                           c->name);
    }
    return add_indicator(sys, (ssx_indicator){.component = component,
                                              .output = -1,
                                              .evaluate = evaluate,
                                              .user = user,
                                              .direction = direction});
}

int ssx_set_indicator_callback(ssx_system *sys, int indicator,
                               int (*evaluate)(void *user, double t, double *value), void *user)
{
    ssx_indicator *ind = system_indicator(sys, indicator);
    if (ind == NULL) {
        return -1;
    }
    if (ind->output >= 0 || evaluate == NULL) {
        return fail_config(sys, ind->component, indicator, NAN,
                           "indicator %d: only a callback indicator takes a function, and "
                           "needs one", indicator);
    }
    ind->evaluate = evaluate;
    ind->user = user;
    return 0;
}

int ssx_set_schedule(ssx_system *sys, const int *order, const int *group_sizes,
                     const int *group_is_loop, int n_groups)
{
    int n = sys->n_components;
    if (order == NULL || group_sizes == NULL || n_groups < 1) {
        return fail_config(sys, -1, -1, NAN, "system '%s': a schedule needs an order and groups",
                           sys->name);
    }
    int total = 0;
    for (int g = 0; g < n_groups; ++g) {
        if (group_sizes[g] < 1) {
            return fail_config(sys, -1, -1, NAN, "system '%s': schedule group %d is empty",
                               sys->name, g);
        }
        total += group_sizes[g];
    }
    if (total != n) {
        return fail_config(sys, -1, -1, NAN,
                           "system '%s': the schedule lists %d components, the system has %d",
                           sys->name, total, n);
    }
    int *seen = calloc((size_t)n + 1, sizeof *seen);
    int *new_order = malloc(((size_t)n + 1) * sizeof *new_order);
    ssx_group *groups = malloc((size_t)n_groups * sizeof *groups);
    if (seen == NULL || new_order == NULL || groups == NULL) {
        free(seen);
        free(new_order);
        free(groups);
        return fail_config(sys, -1, -1, NAN, "out of memory setting the schedule");
    }
    for (int i = 0; i < n; ++i) {
        if (order[i] < 0 || order[i] >= n || seen[order[i]]) {
            free(seen);
            free(new_order);
            free(groups);
            return fail_config(sys, order[i] >= 0 && order[i] < n ? order[i] : -1, -1, NAN,
                               "system '%s': the schedule must list every component exactly once "
                               "(entry %d is %d)",
                               sys->name, i, order[i]);
        }
        seen[order[i]] = 1;
        new_order[i] = order[i];
    }
    for (int g = 0, first = 0; g < n_groups; first += group_sizes[g], ++g) {
        groups[g] = (ssx_group){.first = first,
                                .size = group_sizes[g],
                                .is_loop = group_is_loop != NULL && group_is_loop[g] != 0};
    }
    free(seen);
    free(sys->order);
    free(sys->groups);
    sys->order = new_order;
    sys->groups = groups;
    sys->n_groups = n_groups;
    sys->has_schedule = 1;
    system_structure_changed(sys);
    return 0;
}

int ssx_set_coupling(ssx_system *sys, ssx_coupling coupling)
{
    if (!coupling_known((int)coupling)) {
        return fail_config(sys, -1, -1, NAN, "unknown coupling %d (0 Gauss-Seidel, 1 Jacobi)",
                           (int)coupling);
    }
    sys->coupling = coupling;
    return 0;
}

int ssx_set_threads(ssx_system *sys, int threads)
{
    if (threads < 1 || threads > SSX_MAX_THREADS) {
        return fail_config(sys, -1, -1, NAN, "threads must be between 1 and %d, not %d",
                           SSX_MAX_THREADS, threads);
    }
    sys->threads = threads;
    return 0;
}

int ssx_set_calling_thread_only(ssx_system *sys, int component, int only)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    c->calling_thread_only = only != 0;
    system_structure_changed(sys);
    return 0;
}

int ssx_set_loop_options(ssx_system *sys, double tolerance, int max_iterations, double damping)
{
    if (!(tolerance > 0.0) || !isfinite(tolerance) || max_iterations < 1 || !(damping > 0.0) ||
        !(damping <= 1.0)) {
        return fail_config(
            sys, -1, -1, NAN,
            "loop options: need tolerance > 0, max_iterations >= 1 and 0 < damping <= 1 "
            "(got %g, %d, %g)",
            tolerance, max_iterations, damping);
    }
    sys->loop.tolerance = tolerance;
    sys->loop.max_iterations = max_iterations;
    sys->loop.damping = damping;
    return 0;
}

int ssx_set_loop_jacobian(ssx_system *sys, ssx_loop_jacobian jacobian)
{
    if (jacobian != SSX_JACOBIAN_AUTO && jacobian != SSX_JACOBIAN_FINITE_DIFFERENCES) {
        return fail_config(sys, -1, -1, NAN, "loop Jacobian: unknown mode %d", (int)jacobian);
    }
    sys->loop.jacobian = jacobian;
    return 0;
}

int ssx_set_hybrid_options(ssx_system *sys, double tol_time, double tol_value, int max_iterations,
                           int max_microsteps, int record_internal_steps, ssx_locator locator,
                           double zeno_min_interval)
{
    if (!(tol_time > 0.0) || !isfinite(tol_time) || !(tol_value >= 0.0) || !isfinite(tol_value) ||
        max_iterations < 1 || max_microsteps < 1 || !isfinite(zeno_min_interval) ||
        !locator_known((int)locator)) {
        return fail_config(
            sys, -1, -1, NAN,
            "hybrid options: need tol_time > 0, tol_value >= 0, max_iterations >= 1, "
            "max_microsteps >= 1, a finite zeno_min_interval and a known locator (an "
            "ssx_locator), got locator %d",
            (int)locator);
    }
    sys->hybrid = (ssx_hybrid_options){.tol_time = tol_time,
                                       .tol_value = tol_value,
                                       .max_iterations = max_iterations,
                                       .max_microsteps = max_microsteps,
                                       .record_internal_steps = record_internal_steps != 0,
                                       .locator = locator,
                                       .zeno_min_interval = zeno_min_interval};
    return 0;
}

int ssx_set_monitor(ssx_system *sys, int (*monitor)(void *user, double t), void *user)
{
    sys->monitor.call = monitor;
    sys->monitor.user = user;
    return 0;
}

int ssx_set_output_interval(ssx_system *sys, int grid_steps)
{
    if (grid_steps < 1) {
        return fail_config(
            sys, -1, -1, NAN,
            "system '%s': the output interval is a number of grid steps >= 1, not %d", sys->name,
            grid_steps);
    }
    sys->recording->output_interval = grid_steps;
    return 0;
}

int ssx_set_run_output_interval(ssx_system *sys, int grid_steps)
{
    if (grid_steps < 0) {
        return fail_config(sys, -1, -1, NAN,
                           "system '%s': a run's output interval is a number of grid steps >= 1 "
                           "(or 0 for none), not %d",
                           sys->name, grid_steps);
    }
    sys->recording->run_output_interval = grid_steps;
    return 0;
}

int ssx_set_input_order(ssx_system *sys, int order)
{
    if (order < 0 || order > SSX_MAX_INPUT_ORDER) {
        return fail_config(sys, -1, -1, NAN,
                           "system '%s': the input order is 0, 1 or 2, not %d", sys->name, order);
    }
    sys->input_order = order;
    return 0;
}

int ssx_set_extrapolate_held_inputs(ssx_system *sys, int extrapolate)
{
    sys->extrapolate_held_inputs = extrapolate != 0;
    return 0;
}

int ssx_set_step_control(ssx_system *sys, const ssx_step_control *control)
{
    if (control == NULL) {
        return fail_config(sys, -1, -1, NAN, "step control: no options given");
    }
    ssx_step_control sc = *control;
    if (sc.enabled &&
        !(sc.rtol >= 0.0 && sc.atol >= 0.0 && sc.rtol + sc.atol > 0.0 && isfinite(sc.rtol) &&
          isfinite(sc.atol) && sc.min_step > 0.0 && isfinite(sc.min_step) &&
          (sc.max_step == 0.0 || sc.max_step >= sc.min_step) && isfinite(sc.max_step) &&
          isfinite(sc.initial_step) && sc.safety > 0.0 &&
          sc.safety <= 1.0)) {
        return fail_config(sys, -1, -1, NAN,
                           "system '%s': step control needs rtol >= 0 and atol >= 0 (not both "
                           "0), 0 < min_step <= max_step (finite; 0: no maximum) and 0 < safety <= "
                           "1; got "
                           "rtol=%g atol=%g min_step=%g max_step=%g safety=%g",
                           sys->name, sc.rtol, sc.atol, sc.min_step, sc.max_step, sc.safety);
    }
    /* a step that vanishes in the rounding of the times it starts at never ends */
    if (sc.enabled && sc.min_step < DBL_EPSILON) {
        return fail_config(sys, -1, -1, NAN,
                           "system '%s': step control min_step=%g is below the time resolution "
                           "(%g s, the spacing of times near 1 s): t + min_step would equal t",
                           sys->name, sc.min_step, DBL_EPSILON);
    }
    if (sc.enabled && !(sc.min_change > 0.0 && sc.min_change < 1.0 && sc.max_change > 1.0 &&
                        isfinite(sc.max_change))) {
        return fail_config(sys, -1, -1, NAN,
                           "system '%s': step control needs 0 < min_change < 1 < max_change "
                           "(finite); got min_change=%g max_change=%g",
                           sys->name, sc.min_change, sc.max_change);
    }
    if (sc.enabled && sc.energy &&
        !(sc.proportional_gain >= 0.0 && sc.integral_gain > 0.0 &&
          isfinite(sc.proportional_gain) && isfinite(sc.integral_gain))) {
        return fail_config(sys, -1, -1, NAN,
                           "system '%s': the energy step control needs proportional_gain >= 0 "
                           "and integral_gain > 0 (finite); got %g and %g",
                           sys->name, sc.proportional_gain, sc.integral_gain);
    }
    sys->step_control = sc;
    return 0;
}

int ssx_set_power_bonds(ssx_system *sys, int n_bonds, const int *ends)
{
    if (n_bonds < 0 || (n_bonds > 0 && ends == NULL)) {
        return fail_config(sys, -1, -1, NAN, "system '%s': %d power bonds without their ends",
                           sys->name, n_bonds);
    }
    int *copy = NULL;
    if (n_bonds > 0) {
        copy = malloc(4 * (size_t)n_bonds * sizeof *copy);
        if (copy == NULL) {
            return fail_config(sys, -1, -1, NAN, "out of memory setting the power bonds");
        }
        memcpy(copy, ends, 4 * (size_t)n_bonds * sizeof *copy);
    }
    free(sys->power_bonds);
    sys->power_bonds = copy;
    sys->n_power_bonds = n_bonds;
    return 0;
}
