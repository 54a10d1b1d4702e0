/* Whether a component's outputs are finite: a NaN or an infinity stops the run (unless the
 * system allows them), named with the output and the time. */
#ifndef SSX_FINITE_OUTPUTS_H
#define SSX_FINITE_OUTPUTS_H

#include "component.h"

/* Fails on the first NaN or infinite output, unless the system allows them. */
int component_check_outputs(ssx_system *sys, const ssx_component *c, double t);

#endif
