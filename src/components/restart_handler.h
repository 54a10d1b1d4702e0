/* A declarative event handler run by the engine: an FMU component starts again at the event
 * from its start values, some parameters taken from its outputs at the event (the seed's
 * reinitialize(theta0=theta, omega0=-omega)), without a call into Python. */
#ifndef SSX_RESTART_HANDLER_H
#define SSX_RESTART_HANDLER_H

#include "component.h"
#include "system.h"

typedef struct ssx_restart ssx_restart;

/* Runs c's restart at the event time t: 0, or -1 with the error set. */
int restart_handle(ssx_system *sys, ssx_component *c, double t);
void restart_free(ssx_restart *restart);

#endif
