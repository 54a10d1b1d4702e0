/* Coupling of the components over one macro step (Jacobi or Gauss-Seidel) and at a single
 * instant (consistent outputs at initialization). */
#ifndef SSX_COUPLING_H
#define SSX_COUPLING_H

#include "system.h"

/* coupling names a coupling (an ssx_coupling). */
int coupling_known(int coupling);
/* Chooses the coupling's step and fills the default schedule (add order, no loops) when none
 * was set. */
int coupling_prepare(ssx_system *sys);
/* dst input = scale * src output + offset for every driven input of component c. */
void coupling_propagate_inputs(ssx_system *sys, ssx_component *c);
/* Writes component c's inputs to it and steps it from t to t + h (counted). */
int coupling_step_member(ssx_system *sys, ssx_component *c, double t, double h);
/* Steps every component from t to t + h with the coupling chosen by coupling_prepare. */
static inline int coupling_step(ssx_system *sys, double t, double h)
{
    return sys->coupled_step(sys, t, h);
}
/* Makes all outputs at t consistent with the connections (zero-time evaluation, loops solved). */
int coupling_settle(ssx_system *sys, double t);
/* coupling_settle at ssx_initialize, the system's initial-value problem: drivers first, each
 * component gets its driven inputs before it leaves initialization mode (component_start), so
 * that what it computes on leaving sees them; an algebraic loop's members are iterated in that
 * mode first. */
int coupling_initialize(ssx_system *sys, double t0);

#endif
