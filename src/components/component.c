/* The component interface: dispatch between Python hooks and built-in behaviour, the public
 * built-ins Python calls as super(), and the per-type port batches. */
#include "component.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "restart_handler.h"
#include "system.h"

int component_do_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    sys->stats.do_step_calls++;
    if (c->hooks.do_step != NULL) {
        if (c->hooks.do_step(c->hooks.user, t, dt) != 0) {
            return fail_hook(sys, c, t, "do_step");
        }
        /* an FMU's values were checked where the built-in read them; Python wrote these */
        return c->fmu == NULL ? component_check_outputs(sys, c, t + dt) : 0;
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
        return c->fmu == NULL ? component_check_outputs(sys, c, t) : 0;
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

int component_handle_events(ssx_system *sys, ssx_component *c, const int *indicators, int n,
                            double t)
{
    if (c->hooks.handle_events == NULL) {
        /* built-in: the declarative restart, else no discrete reaction of its own */
        return c->restart != NULL ? restart_handle(sys, c, t) : 0;
    }
    return c->hooks.handle_events(c->hooks.user, indicators, n, t) == 0
               ? 0
               : fail_hook(sys, c, t, "handle_events");
}

int component_initialize(ssx_system *sys, ssx_component *c, double t0)
{
    if (c->hooks.initialize == NULL) {
        return 0;
    }
    return c->hooks.initialize(c->hooks.user, t0) == 0 ? 0 : fail_hook(sys, c, t0, "initialize");
}

int component_record(ssx_system *sys, ssx_component *c, double t)
{
    if (c->hooks.record == NULL) {
        return 0;
    }
    return c->hooks.record(c->hooks.user, t) == 0 ? 0 : fail_hook(sys, c, t, "record");
}

int component_check_outputs(ssx_system *sys, const ssx_component *c, double t)
{
    if (sys->allow_non_finite) {
        return 0;
    }
    for (int i = 0; i < c->n_outputs; ++i) {
        if (!isfinite(c->outputs[i])) {
            return fail_non_finite(sys, c, i, t);
        }
    }
    return 0;
}

int component_can_roll_back(const ssx_component *c)
{
    int has_pair = c->hooks.snapshot != NULL && c->hooks.restore != NULL;
    if (c->ops == &ssx_table_component_ops) {
        return 1; /* a function of time: restoring its outputs restores it */
    }
    if (c->fmu == NULL) {
        return c->can_snapshot && has_pair;
    }
    if (c->hooks.snapshot != NULL || c->hooks.restore != NULL) {
        return has_pair; /* half a pair cannot roll back consistently */
    }
    return c->can_snapshot;
}

static void free_batch(ssx_port_batch *b)
{
    free(b->vr);
    free(b->port);
    memset(b, 0, sizeof *b);
}

static int build_batch(ssx_port_batch *b, const ssx_port *ports, int n_ports, ssx_value_type type)
{
    free_batch(b);
    size_t n = 0;
    for (int i = 0; i < n_ports; ++i) {
        n += ports[i].type == type;
    }
    if (n == 0) {
        return 0;
    }
    b->vr = malloc(n * sizeof *b->vr);
    b->port = malloc(n * sizeof *b->port);
    if (b->vr == NULL || b->port == NULL) {
        free_batch(b);
        return -1;
    }
    for (int i = 0; i < n_ports; ++i) {
        if (ports[i].type == type) {
            b->vr[b->n] = ports[i].vr;
            b->port[b->n] = i;
            b->n++;
        }
    }
    return 0;
}

static void free_prepared(ssx_component *c)
{
    for (int type = 0; type < 3; ++type) {
        free_batch(&c->output_batch[type]);
        free_batch(&c->input_batch[type]);
    }
    free(c->real_scratch);
    free(c->int_scratch);
    free(c->inputs_written);
    free(c->links);
    c->links = NULL;
    c->n_links = 0;
    c->real_scratch = NULL;
    c->int_scratch = NULL;
    c->inputs_written = NULL;
    for (int slot = 0; slot < SSX_SNAPSHOT_SLOTS; ++slot) {
        free(c->saved_outputs[slot]);
        free(c->saved_inputs[slot]);
        c->saved_outputs[slot] = NULL;
        c->saved_inputs[slot] = NULL;
    }
}

int component_prepare(ssx_component *c)
{
    free_prepared(c);
    for (int type = 0; type < 3; ++type) {
        if (build_batch(&c->output_batch[type], c->output_ports, c->n_outputs,
                        (ssx_value_type)type) != 0 ||
            build_batch(&c->input_batch[type], c->input_ports, c->n_inputs,
                        (ssx_value_type)type) != 0) {
            return -1;
        }
    }
    size_t widest = (size_t)(c->n_outputs > c->n_inputs ? c->n_outputs : c->n_inputs) + 1;
    c->real_scratch = malloc(widest * sizeof *c->real_scratch);
    c->int_scratch = malloc(widest * sizeof *c->int_scratch);
    c->inputs_written = malloc(((size_t)c->n_inputs + 1) * sizeof *c->inputs_written);
    c->inputs_written_epoch = -1;
    if (c->real_scratch == NULL || c->int_scratch == NULL || c->inputs_written == NULL) {
        return -1;
    }
    for (int slot = 0; slot < SSX_SNAPSHOT_SLOTS; ++slot) {
        c->saved_outputs[slot] = calloc((size_t)c->n_outputs + 1, sizeof(double));
        c->saved_inputs[slot] = calloc((size_t)c->n_inputs + 1, sizeof(double));
        if (c->saved_outputs[slot] == NULL || c->saved_inputs[slot] == NULL) {
            return -1;
        }
    }
    return 0;
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
    free_prepared(c);
    own_event_list_free(&c->own_events);
    restart_free(c->restart);
    free(c->name);
    free(c->output_ports);
    free(c->outputs);
    free(c->input_ports);
    free(c->inputs);
    free(c->input_starts);
    free(c->input_driver);
    free(c);
}

/* Public built-ins: what a Python override reaches as super(); never a hook, never counted. */

int ssx_component_do_step(ssx_system *sys, int component, double t, double dt)
{
    ssx_component *c = system_component(sys, component);
    return c == NULL ? -1 : c->ops->do_step(sys, c, t, dt);
}

int ssx_component_write_inputs(ssx_system *sys, int component)
{
    ssx_component *c = system_component(sys, component);
    return c == NULL ? -1 : c->ops->write_inputs(sys, c);
}

int ssx_component_read_outputs(ssx_system *sys, int component)
{
    ssx_component *c = system_component(sys, component);
    return c == NULL ? -1 : c->ops->read_outputs(sys, c);
}

int ssx_component_snapshot(ssx_system *sys, int component, int slot)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (slot < 0 || slot >= SSX_SNAPSHOT_SLOTS) {
        return fail(sys, component, -1, sys->time, "component '%s': snapshot slot %d out of range",
                    c->name, slot);
    }
    return c->ops->snapshot(sys, c, slot);
}

int ssx_component_restore(ssx_system *sys, int component, int slot, double t)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (slot < 0 || slot >= SSX_SNAPSHOT_SLOTS) {
        return fail(sys, component, -1, t, "component '%s': snapshot slot %d out of range",
                    c->name, slot);
    }
    return c->ops->restore(sys, c, slot, t);
}
