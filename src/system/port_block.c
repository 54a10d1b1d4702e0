/* Every component's port values in one block, in schedule order (see port_block.h). */
#include "port_block.h"

#include <stdlib.h>
#include <string.h>

#include "component.h"
#include "error.h"

/* Whether every member's ports already lie in the block where the schedule puts them. */
static int laid_out(const ssx_system *sys, size_t total)
{
    if (sys->port_block == NULL || total != sys->port_block_size) {
        return 0;
    }
    size_t at = 0;
    for (int k = 0; k < sys->n_components; ++k) {
        const ssx_component *c = sys->components[sys->order[k]];
        if (!c->ports_in_block || c->inputs != sys->port_block + at ||
            c->outputs != sys->port_block + at + c->n_inputs) {
            return 0;
        }
        at += (size_t)c->n_inputs + (size_t)c->n_outputs;
    }
    return 1;
}

static void copy_values(double *to, const double *from, int n)
{
    if (n > 0) {
        memcpy(to, from, (size_t)n * sizeof *to);
    }
}

int port_block_lay_out(ssx_system *sys)
{
    size_t total = 0;
    for (int i = 0; i < sys->n_components; ++i) {
        total += (size_t)sys->components[i]->n_inputs + (size_t)sys->components[i]->n_outputs;
    }
    if (laid_out(sys, total)) {
        return 0;
    }
    double *block = malloc((total + 1) * sizeof *block);
    if (block == NULL) {
        return fail(sys, -1, -1, sys->time, "out of memory laying out the port values of '%s'",
                    sys->name);
    }
    size_t at = 0;
    for (int k = 0; k < sys->n_components; ++k) {
        ssx_component *c = sys->components[sys->order[k]];
        double *inputs = block + at;
        double *outputs = inputs + c->n_inputs;
        copy_values(inputs, c->inputs, c->n_inputs);
        copy_values(outputs, c->outputs, c->n_outputs);
        if (!c->ports_in_block) {
            free(c->inputs);
            free(c->outputs);
        }
        c->inputs = inputs;
        c->outputs = outputs;
        c->ports_in_block = 1;
        at += (size_t)c->n_inputs + (size_t)c->n_outputs;
    }
    free(sys->port_block); /* no component points into it any more */
    sys->port_block = block;
    sys->port_block_size = total;
    return 0;
}

/* A copy of n values in an allocation of its own (one more than needed: never size 0). */
static double *own_copy(const double *values, int n)
{
    double *copy = malloc(((size_t)n + 1) * sizeof *copy);
    if (copy != NULL) {
        copy_values(copy, values, n);
    }
    return copy;
}

int port_block_detach(ssx_component *c)
{
    if (!c->ports_in_block) {
        return 0;
    }
    double *inputs = own_copy(c->inputs, c->n_inputs);
    double *outputs = own_copy(c->outputs, c->n_outputs);
    if (inputs == NULL || outputs == NULL) {
        free(inputs);
        free(outputs);
        return -1;
    }
    c->inputs = inputs;
    c->outputs = outputs;
    c->ports_in_block = 0;
    return 0;
}

void port_block_free(ssx_system *sys)
{
    free(sys->port_block);
    sys->port_block = NULL;
    sys->port_block_size = 0;
}
