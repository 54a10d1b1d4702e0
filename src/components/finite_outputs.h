/* Whether a component's outputs are finite. A NaN or an infinity that reaches something (a
 * connected input, an event indicator, and through the connections a step control) stops the
 * run, named with the output and the time; one that feeds nothing is recorded, and the time it
 * first appeared is kept for the caller to warn of. Either way when the system allows them,
 * nothing is checked. */
#ifndef SSX_FINITE_OUTPUTS_H
#define SSX_FINITE_OUTPUTS_H

#include "component.h"

/* Marks the outputs that feed a connection and forgets every first time (at ssx_initialize,
 * once the components are prepared); the indicators then mark the outputs they read
 * (indicators_watch_outputs, stepping/events/indicator.h). */
void finite_outputs_watch(ssx_system *sys);

/* Fails on the first NaN or infinite output that feeds something, unless the system allows
 * them; keeps the first time of the others. */
int component_check_outputs(ssx_system *sys, ssx_component *c, double t);

#endif
