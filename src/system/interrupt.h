/* Stopping a run inside a step: every loop of the engine that may run long (the step
 * control's retries and steps, the localization's trials, an algebraic loop's iterations, a
 * Model Exchange component's integrator steps) asks here each time round, as the time loop
 * asks after each macro step, so Ctrl-C and the run's timeout stop it within about one
 * monitor interval plus one stride (monitor.h), not at the next grid point. */
#ifndef SSX_INTERRUPT_H
#define SSX_INTERRUPT_H

#include "system.h"

/* 0 to go on; -1 when the monitor stops the run at t, with the run's error set (kind
 * SSX_ERROR_CALLBACK). A pass costs a decrement between two readings of the clock. Outside a
 * run (ssx_initialize) and while a batch of components steps on the system's threads nobody
 * asks: the monitor runs on the run's thread alone, and the batch's join follows its steps. */
int run_interrupted(ssx_system *sys, double t);

#endif
