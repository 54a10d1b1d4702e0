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
/* After a step of length h: the root mean square over the bonds of
 * |dP| h / (atol + rtol max(|P_a|, |P_b|) h), with the inputs the components reached. */
double energy_residual_error(const ssx_system *sys, double h);

#endif
