/* Calling a component (see component_calls.h). */
#include "component_calls.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "own_events.h"
#include "system.h"

const component_state_ops component_no_saved_state = {0};

int component_do_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    sys->stats.do_step_calls++;
    if (c->has_step_hook) {
        if (c->hooks.do_step(c->hooks.user, t, dt) != 0) {
            return fail_hook(sys, c, t, "do_step");
        }
        /* an FMU's values were checked where the built-in read them; Python wrote these */
        return c->ops->checks_own_outputs ? 0 : component_check_outputs(sys, c, t + dt);
    }
    return c->ops->do_step(sys, c, t, dt);
}

int component_write_inputs(ssx_system *sys, ssx_component *c)
{
    return c->ops->write_inputs(sys, c);
}

int component_read_outputs(ssx_system *sys, ssx_component *c)
{
    return c->ops->read_outputs(sys, c);
}

int component_evaluate_outputs(ssx_system *sys, ssx_component *c, double t)
{
    if (c->hooks.evaluate_outputs != NULL) {
        if (c->hooks.evaluate_outputs(c->hooks.user, t) != 0) {
            return fail_hook(sys, c, t, "evaluate_outputs");
        }
        return c->ops->checks_own_outputs ? 0 : component_check_outputs(sys, c, t);
    }
    return c->ops->evaluate_outputs(sys, c, t);
}

int component_snapshot(ssx_system *sys, ssx_component *c, int slot)
{
    sys->stats.state_saves++;
    if (c->n_outputs > 0) {
        memcpy(c->saved_outputs[slot], c->outputs, (size_t)c->n_outputs * sizeof(double));
    }
    if (c->n_inputs > 0) {
        memcpy(c->saved_inputs[slot], c->inputs, (size_t)c->n_inputs * sizeof(double));
    }
    if (c->hooks.snapshot != NULL) {
        return c->hooks.snapshot(c->hooks.user, slot) == 0
                   ? 0
                   : fail_hook(sys, c, sys->time, "snapshot");
    }
    return c->ops->snapshot(sys, c, slot);
}

int component_restore(ssx_system *sys, ssx_component *c, int slot, double t)
{
    sys->stats.state_restores++;
    int status;
    if (c->hooks.restore != NULL) {
        status = c->hooks.restore(c->hooks.user, slot, t) == 0 ? 0
                                                                : fail_hook(sys, c, t, "restore");
    } else {
        status = c->ops->restore(sys, c, slot, t);
    }
    if (status != 0) {
        return -1;
    }
    if (c->n_outputs > 0) {
        memcpy(c->outputs, c->saved_outputs[slot], (size_t)c->n_outputs * sizeof(double));
    }
    if (c->n_inputs > 0) {
        memcpy(c->inputs, c->saved_inputs[slot], (size_t)c->n_inputs * sizeof(double));
    }
    own_events_drop_after(c, t);
    return 0;
}

int component_handle_events(ssx_system *sys, ssx_component *c, const int *sources, int n,
                            double t_event, double t)
{
    if (c->hooks.handle_events == NULL) {
        /* built-in: the kind's own reaction (an FMU's declarative restart), if any */
        return c->ops->handle_events != NULL ? c->ops->handle_events(sys, c, t) : 0;
    }
    return c->hooks.handle_events(c->hooks.user, sources, n, t_event) == 0
               ? 0
               : fail_hook(sys, c, t_event, "handle_events");
}

int component_initialize(ssx_system *sys, ssx_component *c, double t0)
{
    if (c->hooks.initialize == NULL) {
        return 0;
    }
    return c->hooks.initialize(c->hooks.user, t0) == 0 ? 0 : fail_hook(sys, c, t0, "initialize");
}

int component_initial_outputs(ssx_system *sys, ssx_component *c, double t0)
{
    if (c->hooks.evaluate_outputs == NULL && c->ops->initial_outputs != NULL) {
        return c->ops->initial_outputs(sys, c, t0);
    }
    return component_evaluate_outputs(sys, c, t0);
}

int component_start(ssx_system *sys, ssx_component *c, double t0)
{
    if (c->ops->leave_initialization != NULL && c->ops->leave_initialization(sys, c, t0) != 0) {
        return -1;
    }
    if (component_initialize(sys, c, t0) != 0) {
        return -1;
    }
    return c->ops->adopt_inputs != NULL ? c->ops->adopt_inputs(sys, c, t0) : 0;
}

int component_record(ssx_system *sys, ssx_component *c, double t)
{
    if (c->hooks.record == NULL) {
        return 0;
    }
    return c->hooks.record(c->hooks.user, t) == 0 ? 0 : fail_hook(sys, c, t, "record");
}

int component_can_roll_back(const ssx_component *c)
{
    return c->ops->can_roll_back(c);
}

void component_unprepare(ssx_component *c)
{
    c->links = NULL;
    c->n_links = 0;
    c->output_watch = NULL;
    for (int slot = 0; slot < SSX_SNAPSHOT_SLOTS; ++slot) {
        c->saved_outputs[slot] = NULL;
        c->saved_inputs[slot] = NULL;
    }
    if (c->ops->unprepare != NULL) {
        c->ops->unprepare(c);
    }
}

size_t component_prepared_bytes(const ssx_component *c)
{
    /* a link, a snapshot copy and a watch per port, and about as much again for what the kind
     * builds */
    size_t ports = (size_t)c->n_inputs + (size_t)c->n_outputs + 2;
    return ports * (sizeof(ssx_input_link) + sizeof(ssx_output_watch) +
                    (SSX_SNAPSHOT_SLOTS + 3) * sizeof(double));
}

int component_prepare(ssx_system *sys, ssx_component *c)
{
    /* one more than needed: never a block of size 0 */
    c->links = arena_allocate(&sys->prepared_blocks,
                              ((size_t)c->n_inputs + 1) * sizeof *c->links, sizeof(double));
    if (c->links == NULL) {
        return -1;
    }
    return c->ops->prepare != NULL ? c->ops->prepare(sys, c) : 0;
}

int component_prepare_snapshots(ssx_system *sys, ssx_component *c)
{
    size_t n_saved = (size_t)c->n_outputs + (size_t)c->n_inputs + 2;
    double *saved = arena_allocate(&sys->prepared_blocks,
                                   SSX_SNAPSHOT_SLOTS * n_saved * sizeof(double), sizeof(double));
    if (saved == NULL) {
        return -1;
    }
    for (int slot = 0; slot < SSX_SNAPSHOT_SLOTS; ++slot) {
        c->saved_outputs[slot] = saved;
        c->saved_inputs[slot] = saved + c->n_outputs + 1;
        saved += n_saved;
    }
    /* read only when an output is not finite: among the cold copies */
    c->output_watch = arena_allocate(&sys->prepared_blocks,
                                     ((size_t)c->n_outputs + 1) * sizeof *c->output_watch,
                                     sizeof(double));
    return c->output_watch != NULL ? 0 : -1; /* filled by finite_outputs_watch */
}

void component_free(ssx_component *c)
{
    if (c == NULL) {
        return;
    }
    /* FMU states stay with their (borrowed) instance, which releases them when it is freed;
     * Python snapshots go with the Python objects that hold them. */
    if (c->ops->release != NULL) {
        c->ops->release(c);
    }
    own_event_list_free(&c->own_events);
    free(c->name);
    free(c->output_ports);
    free(c->input_ports);
    if (!c->ports_in_block) { /* else the system frees the block */
        free(c->outputs);
        free(c->inputs);
    }
    free(c->input_starts);
    free(c->input_driver);
    /* the block itself is the system's (system_add_component) */
}
