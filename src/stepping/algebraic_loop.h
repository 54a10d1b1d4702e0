/* Solving an algebraic loop: the real inputs of a schedule group driven by the group's own
 * outputs, so that input = scale * output + offset holds at one instant. */
#ifndef SSX_ALGEBRAIC_LOOP_H
#define SSX_ALGEBRAIC_LOOP_H

#include "system.h"

int loop_solve(ssx_system *sys, const ssx_group *group, double t);

#endif
