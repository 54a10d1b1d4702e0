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

/* Component `component` if it can take a port of `type`, else NULL with the error set. */
static ssx_component *port_owner(ssx_system *sys, int component, ssx_value_type type)
{
    ssx_component *c = system_component(sys, component);
    if (c != NULL && !(type >= SSX_REAL && type <= SSX_BINARY)) {
        fail_config(sys, component, -1, NAN, "component '%s': unknown value type %d", c->name,
                    (int)type);
        return NULL;
    }
    return c;
}

/* `array` grown to `count` elements of `size` bytes; where that fails, `array` as it was (the
 * component still owns and frees it) and *failed set. */
static void *grown(void *array, size_t count, size_t size, int *failed)
{
    void *bigger = realloc(array, count * size);
    if (bigger == NULL) {
        *failed = 1;
        return array;
    }
    return bigger;
}

static int out_of_memory(ssx_system *sys, const ssx_component *c, const char *port)
{
    return fail_config(sys, c->index, -1, NAN, "out of memory adding %s to '%s'", port, c->name);
}

int ssx_add_output(ssx_system *sys, int component, ssx_value_type type, unsigned int vr)
{
    ssx_component *c = port_owner(sys, component, type);
    if (c == NULL) {
        return -1;
    }
    if (port_block_detach(c) != 0) {
        return out_of_memory(sys, c, "an output");
    }
    size_t n = (size_t)c->n_outputs + 1;
    int failed = 0;
    c->output_ports = grown(c->output_ports, n, sizeof *c->output_ports, &failed);
    c->outputs = grown(c->outputs, n, sizeof *c->outputs, &failed);
    if (failed) {
        return out_of_memory(sys, c, "an output");
    }
    c->output_ports[c->n_outputs] = (ssx_port){.type = type, .vr = vr};
    c->outputs[c->n_outputs] = 0.0;
    system_structure_changed(sys);
    return c->n_outputs++;
}

int ssx_add_input(ssx_system *sys, int component, ssx_value_type type, unsigned int vr,
                  double start)
{
    ssx_component *c = port_owner(sys, component, type);
    if (c == NULL) {
        return -1;
    }
    if (isinf(start) || (isnan(start) && c->ops->adopt_inputs == NULL)) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s': the start value of an input must "
                           "be finite (NaN, the FMU's own value, exists for FMU components only)",
                           c->name);
    }
    if (port_block_detach(c) != 0) {
        return out_of_memory(sys, c, "an input");
    }
    size_t n = (size_t)c->n_inputs + 1;
    int failed = 0;
    c->input_ports = grown(c->input_ports, n, sizeof *c->input_ports, &failed);
    c->inputs = grown(c->inputs, n, sizeof *c->inputs, &failed);
    c->input_starts = grown(c->input_starts, n, sizeof *c->input_starts, &failed);
    c->input_driver = grown(c->input_driver, n, sizeof *c->input_driver, &failed);
    if (failed) {
        return out_of_memory(sys, c, "an input");
    }
    c->input_ports[c->n_inputs] = (ssx_port){.type = type, .vr = vr};
    c->inputs[c->n_inputs] = start;
    c->input_starts[c->n_inputs] = start;
    c->input_driver[c->n_inputs] = -1;
    system_structure_changed(sys);
    return c->n_inputs++;
}
