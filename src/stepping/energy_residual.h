/* ECCO's error measure (Sadjina et al., energy-conservation-based co-simulation): across a power
 * bond each side computes the power it receives as its input times its own output (a torque
 * times the angular velocity it gives back). With exact coupling the two agree; with inputs that
 * lag their drivers they differ, and the difference over a step is energy the coupling created
 * or lost. */
#ifndef SSX_ENERGY_RESIDUAL_H
#define SSX_ENERGY_RESIDUAL_H

#include "system.h"

/* Each bond's two inputs are driven by Real outputs of the other side (ssx_initialize). */
int energy_residual_check(ssx_system *sys);
/* Bond b's |dP| h / (atol + rtol max(|P_a|, |P_b|) h) over a step of length h, with the
 * inputs and outputs as they are now. */
double energy_residual_bond(const ssx_system *sys, int bond, double h);
/* After a step of length h: the root mean square over the bonds of their residuals, each
 * measured[b] where that is a number (a bond measured before an algebraic loop corrected its
 * inputs), else measured now with the inputs the components reached. */
double energy_residual_error(const ssx_system *sys, double h, const double *measured);

#endif
