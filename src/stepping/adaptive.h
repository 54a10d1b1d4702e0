/* Error-controlled communication steps (ssx_set_step_control): the master algorithm that
 * chooses each coupled step's length from the coupling error of the last one (input_order.h),
 * with rollback (a step over tolerance is taken again, shorter) or without (only the next steps
 * adapt). Its state is its own workspace. */
#ifndef SSX_ADAPTIVE_H
#define SSX_ADAPTIVE_H

#include "system.h"

/* Makes the step controller's state (sys->adaptive) and, when the system has event
 * indicators, the hybrid algorithm's workspace in *workspace. */
int adaptive_prepare(ssx_system *sys, void **workspace);
/* Covers the grid interval [t, t_next] from `from` with accepted steps, up to its end or the
 * first event inside (located and handled as the hybrid algorithm does; *event set). Records
 * the grid point t_next when it gets there without an event. */
int adaptive_step(ssx_system *sys, double t, double from, double t_next, int *event);
/* What it carries between steps (algorithm.h): the hybrid algorithm's carried[0], then the
 * next step's proposed length and the last accepted step's error. */
void adaptive_carry_out(const ssx_system *sys, double *carried);
void adaptive_carry_in(ssx_system *sys, const double *carried);
/* Frees both. */
void adaptive_release(ssx_system *sys, void *workspace);

#endif
