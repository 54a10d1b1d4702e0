/* What an FMU reports besides a call's status, in the binding's version-neutral words: the
 * back-ends fill them, the engine reads them. */
#ifndef SSX_FMU_OUTCOME_H
#define SSX_FMU_OUTCOME_H

/* What an FMI 3.0 doStep returns besides its status. `reported` is 0 when the standard says
 * nothing more than the status (FMI 2.0); event_handling_needed is 1 only for an instance made
 * with eventModeUsed. */
typedef struct {
    int reported;
    int event_handling_needed;
    int terminate_simulation;
    int early_return;
    double last_successful_time;
    /* the step ended at a tick of the FMU's periodic input clocks (FMI 3.0 Co-Simulation):
     * the engine ticks them there (ssx_fmu_tick_clocks) in event mode */
    int clock_tick;
    /* the FMU cannot return early (FMI 3.0 Co-Simulation with event mode): an event it reports
     * at the step's end happened somewhere inside the step */
    int events_at_step_end;
} fmu_step_outcome;

/* What fmi2NewDiscreteStates (fmi2EventInfo, Model Exchange) and fmi3UpdateDiscreteStates
 * (FMI 3.0 Co-Simulation in event mode) tell, version-neutral. */
typedef struct {
    int new_discrete_states_needed;
    int terminate_simulation;
    int nominals_changed;
    int values_changed;
    int next_event_time_defined;
    double next_event_time;
} ssx_fmu_event_info;

#endif
