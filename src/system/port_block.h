/* Every component's port values in one block of doubles, in schedule order: each member's
 * inputs, then its outputs, then the next member's. The coupling loop then walks memory in the
 * order it steps, a link reads the output just written before it, and a recorded sample reads
 * one run of memory, instead of two allocations of their own per component, scattered where
 * they were made.
 *
 * Laid out at ssx_initialize, after the schedule: the arrays move there once (Python takes
 * their addresses again after initialize) and stay while the structure does not change, so
 * that a System initialized again keeps them where they are. */
#ifndef SSX_PORT_BLOCK_H
#define SSX_PORT_BLOCK_H

#include "system.h"

/* Moves every component's port values into the block in schedule order, unless they are
 * already there; 0, or -1 with the error set (out of memory: nothing moved). */
int port_block_lay_out(ssx_system *sys);
/* Gives c its own port arrays again (before a port is added to it): 0, or -1 out of memory. */
int port_block_detach(ssx_component *c);
/* Frees the block: the components that point into it are freed first. */
void port_block_free(ssx_system *sys);

#endif
