/* Stepping for every interface's doStep call. */
#ifndef SYSSIMX_FMU_STEP_H
#define SYSSIMX_FMU_STEP_H

#include "fmu_instance.h"

/* When the model asks to stop (INFINITY when it never does). */
double fmu_stop_time(const fmu_instance *inst);

/* Advances the instance from communication point t by h: to t + h, or only to the time the
 * model asks to stop, or (importer_handles_events) only to the first internal event, which it
 * leaves pending. A step that ends where the instance already is only refreshes the outputs.
 * `function` names the call in messages. */
fmu_status fmu_do_step(fmu_instance *inst, const char *function, double t, double h);

#endif
