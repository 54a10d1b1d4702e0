/* The values of a component's driven inputs from the outputs that drive them (the links the
 * coupling builds at initialize): shared by the coupling and the input order, which both set
 * inputs and must not need each other. */
#ifndef SSX_INPUT_LINKS_H
#define SSX_INPUT_LINKS_H

#include "component.h"

static inline void input_links_apply(ssx_component *c)
{
    const ssx_input_link *links = c->links;
    for (int i = 0; i < c->n_links; ++i) {
        c->inputs[links[i].input] = links[i].scale * *links[i].source + links[i].offset;
    }
}

#endif
