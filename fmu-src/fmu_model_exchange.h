/* The Model Exchange interface, version-neutral: what the fmi2 and fmi3 entry points do once
 * they checked the call is allowed in the instance's state. `function` names the call in
 * messages. */
#ifndef SYSSIMX_FMU_MODEL_EXCHANGE_H
#define SYSSIMX_FMU_MODEL_EXCHANGE_H

#include "fmu_instance.h"

/* What an event iteration tells the importer (fmi2EventInfo, fmi3UpdateDiscreteStates). */
typedef struct {
    int terminate;
    int values_changed;
    int next_event_time_defined;
    double next_event_time;
} fmu_discrete_update;

fmu_status fmu_me_set_time(fmu_instance *inst, const char *function, double time);
fmu_status fmu_me_set_states(fmu_instance *inst, const char *function, const double *x,
                             size_t nx);
fmu_status fmu_me_get_states(fmu_instance *inst, const char *function, double *x, size_t nx);
fmu_status fmu_me_derivatives(fmu_instance *inst, const char *function, double *dx, size_t nx);
fmu_status fmu_me_event_indicators(fmu_instance *inst, const char *function, double *z,
                                   size_t nz);
fmu_status fmu_me_nominals(fmu_instance *inst, const char *function, double *nominals,
                           size_t nx);
/* The model's events since the last event mode, applied; one pass settles them. */
void fmu_me_update_discrete_states(fmu_instance *inst, fmu_discrete_update *update);
/* Whether the model asks to end the simulation at the instance's time. */
int fmu_me_terminates(const fmu_instance *inst);

#endif
