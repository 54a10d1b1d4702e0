/* The model's equations applied to an instance: its outputs, events and indicators at the
 * instance's time and state, the back-end's parameters, and the inputs along their motion inside
 * a step. The life cycle, the step, Model Exchange and the solver back-ends call it; it calls
 * none of them, so a back-end never needs the rooms that drive it. */
#ifndef SYSSIMX_FMU_EVALUATION_H
#define SYSSIMX_FMU_EVALUATION_H

#include "fmu_instance.h"

/* Value of the back-end parameter with index `i` in the back-end's variable table. */
double fmu_solver_parameter(const fmu_instance *inst, size_t i);

/* Recompute outputs and locals from the current state and inputs; clears outputs_stale. */
void fmu_refresh_outputs(fmu_instance *inst);

/* The model's event indicators at the instance's time and state, into z. */
void fmu_event_indicators(const fmu_instance *inst, double *z);

/* Apply the internal events the back-end marked in inst->fired at time t (changes x), and log
 * them. */
void fmu_handle_events(fmu_instance *inst, double t, double *x);

/* The inputs at time t inside a step, along their motion (fmu_interpolation.h). */
void fmu_inputs_follow(fmu_instance *inst, double t);

/* The back-ends call this before evaluating the model at time t inside a step: the inputs take
 * their interpolated values at t. Inline: it runs at every right-hand side evaluation. */
static inline void fmu_inputs_at(fmu_instance *inst, double t)
{
    if (inst->input_motion != INPUTS_HELD)
        fmu_inputs_follow(inst, t);
}

#endif
