/* Adding a component and its ports (component_setup.h). */
#define _POSIX_C_SOURCE 200809L

#include "component_setup.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "arena.h"
#include "array.h"
#include "component.h"
#include "error.h"
#include "port_block.h"
#include "round_up.h"

/* A component block starts on a cache line: the fields a step reads lead it. */
enum { COMPONENT_ALIGNMENT = 64 };

_Static_assert(offsetof(ssx_component, has_step_hook) + sizeof(int) <= COMPONENT_ALIGNMENT,
               "what every step reads must stay in the component's first cache line");

int system_add_component(ssx_system *sys, const char *name, int can_snapshot,
                         const ssx_component_ops *ops, size_t data_size)
{
    if (name == NULL || name[0] == '\0') {
        return fail_config(sys, -1, -1, NAN, "system '%s': a component needs a non-empty name",
                           sys->name);
    }
    for (int i = 0; i < sys->n_components; ++i) {
        if (strcmp(sys->components[i]->name, name) == 0) {
            return fail_config(sys, i, -1, NAN, "system '%s' already has a component named '%s'",
                               sys->name, name);
        }
    }
    if (array_reserve((void **)&sys->components, &sys->components_capacity,
                      (size_t)sys->n_components + 1, sizeof *sys->components, 8) != 0) {
        return fail_config(sys, -1, -1, NAN, "out of memory adding component '%s'", name);
    }
    /* data read on every step sits next to the ports' pointers, not in a block of its own,
     * starting on a cache line of its own; the blocks of a system's components lie side by
     * side in the order they were added */
    size_t head = round_up(sizeof(ssx_component), COMPONENT_ALIGNMENT);
    ssx_component *c = arena_allocate(&sys->component_blocks, head + data_size,
                                      COMPONENT_ALIGNMENT);
    if (c == NULL || (c->name = strdup(name)) == NULL) {
        return fail_config(sys, -1, -1, NAN, "out of memory adding component '%s'", name);
    }
    c->index = sys->n_components;
    c->ops = ops;
    c->data = data_size > 0 ? (void *)((char *)c + head) : NULL;
    c->can_snapshot = can_snapshot != 0;
    sys->components[sys->n_components++] = c;
    system_structure_changed(sys);
    return c->index;
}

static int valid_type(ssx_value_type type)
{
    return type >= SSX_REAL && type <= SSX_BINARY;
}

int ssx_add_output(ssx_system *sys, int component, ssx_value_type type, unsigned int vr)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (!valid_type(type)) {
        return fail_config(sys, component, -1, NAN, "component '%s': unknown value type %d",
                           c->name, (int)type);
    }
    if (port_block_detach(c) != 0) {
        return fail_config(sys, component, -1, NAN, "out of memory adding an output to '%s'",
                           c->name);
    }
    size_t n = (size_t)c->n_outputs + 1;
    ssx_port *ports = realloc(c->output_ports, n * sizeof *ports);
    if (ports != NULL) {
        c->output_ports = ports;
    }
    double *values = realloc(c->outputs, n * sizeof *values);
    if (values != NULL) {
        c->outputs = values;
    }
    if (ports == NULL || values == NULL) {
        return fail_config(sys, component, -1, NAN, "out of memory adding an output to '%s'",
                           c->name);
    }
    c->output_ports[c->n_outputs] = (ssx_port){.type = type, .vr = vr};
    c->outputs[c->n_outputs] = 0.0;
    system_structure_changed(sys);
    return c->n_outputs++;
}

int ssx_add_input(ssx_system *sys, int component, ssx_value_type type, unsigned int vr,
                  double start)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (!valid_type(type)) {
        return fail_config(sys, component, -1, NAN, "component '%s': unknown value type %d",
                           c->name, (int)type);
    }
    if (isinf(start) || (isnan(start) && c->ops->adopt_inputs == NULL)) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s': the start value of an input must "
                           "be finite (NaN, the FMU's own value, exists for FMU components only)",
                           c->name);
    }
    if (port_block_detach(c) != 0) {
        return fail_config(sys, component, -1, NAN, "out of memory adding an input to '%s'",
                           c->name);
    }
    size_t n = (size_t)c->n_inputs + 1;
    ssx_port *ports = realloc(c->input_ports, n * sizeof *ports);
    if (ports != NULL) {
        c->input_ports = ports;
    }
    double *values = realloc(c->inputs, n * sizeof *values);
    if (values != NULL) {
        c->inputs = values;
    }
    double *starts = realloc(c->input_starts, n * sizeof *starts);
    if (starts != NULL) {
        c->input_starts = starts;
    }
    int *drivers = realloc(c->input_driver, n * sizeof *drivers);
    if (drivers != NULL) {
        c->input_driver = drivers;
    }
    if (ports == NULL || values == NULL || starts == NULL || drivers == NULL) {
        return fail_config(sys, component, -1, NAN, "out of memory adding an input to '%s'",
                           c->name);
    }
    c->input_ports[c->n_inputs] = (ssx_port){.type = type, .vr = vr};
    c->inputs[c->n_inputs] = start;
    c->input_starts[c->n_inputs] = start;
    c->input_driver[c->n_inputs] = -1;
    system_structure_changed(sys);
    return c->n_inputs++;
}
