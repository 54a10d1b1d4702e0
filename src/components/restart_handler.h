/* A declarative event handler run by the engine: an FMU component starts again at the event
 * from its start values, some parameters taken from its outputs at the event (the seed's
 * reinitialize(theta0=theta, omega0=-omega)), without a call into Python. */
#ifndef SSX_RESTART_HANDLER_H
#define SSX_RESTART_HANDLER_H

#include "component.h"
#include "fmu_binding.h"
#include "system.h"

typedef struct ssx_restart ssx_restart;

/* The restart ssx_set_restart_handler describes, for component c (its sources checked by the
 * caller); NULL with the error set when out of memory. */
ssx_restart *restart_new(ssx_system *sys, const ssx_component *c,
                         const ssx_fmu_experiment *experiment, const ssx_fmu_values *starts,
                         const unsigned int *vr, const int *source, const double *scale,
                         const double *offset, size_t n);
/* Starts c's FMU `fmu` again at the event time t; the caller reads its outputs. 0, or -1 with
 * the error set. */
int restart_handle(ssx_system *sys, ssx_component *c, ssx_fmu *fmu, ssx_restart *r, double t);
/* The start value of vr of `type` (a Boolean: nonzero is true) becomes `value`: 0, or -1
 * when vr is not among the restart's start values of that type. */
int restart_set_start(ssx_restart *r, ssx_value_type type, unsigned int vr, double value);
void restart_free(ssx_restart *restart);

#endif
