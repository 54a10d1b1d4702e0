/* The whole system's snapshot and restore, component by component: what the algorithms that
 * roll back (hybrid, adaptive) call. */
#ifndef SSX_SYSTEM_STATE_H
#define SSX_SYSTEM_STATE_H

#include "system.h"

/* Every component's snapshot into slot, or back from it at time t (observers are told). */
int system_snapshot(ssx_system *sys, int slot);
int system_restore(ssx_system *sys, int slot, double t);

#endif
