/* Adding a component to the system and ports to a component: what the component kinds call
 * when they are added, and the public calls that build a system (ssx_add_input,
 * ssx_add_output). */
#ifndef SSX_COMPONENT_SETUP_H
#define SSX_COMPONENT_SETUP_H

#include "component.h"
#include "system.h"

/* Appends a component of the given kind, with data_size bytes of zeroed data for the kind in
 * the same block (c->data; NULL for 0: the kind sets its own); returns its index, or -1 with
 * the error set. */
int system_add_component(ssx_system *sys, const char *name, int can_snapshot,
                         const ssx_component_ops *ops, size_t data_size);

#endif
