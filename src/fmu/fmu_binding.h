/* Internal helpers of the FMU binding that the engine needs beyond the public ssx_fmu_* calls. */
#ifndef SSX_FMU_BINDING_H
#define SSX_FMU_BINDING_H

#include "fmu_outcome.h"
#include "fmu_remote.h"
#include "syssimx_engine.h"

/* Counts instantiations: FMU states of an earlier instance are invalid (the binding frees them
 * when their instance goes away), so a holder compares generations before reusing a state. A
 * reset keeps the instance and its generation. */
long ssx_fmu_generation(const ssx_fmu *fmu);
/* Counts the starts of an instance from its start values: instantiations and resets. A Model
 * Exchange holder runs its first event iteration again when it changed. */
long ssx_fmu_starts(const ssx_fmu *fmu);
/* Counts the calls that may change the instance's inputs: fmi2Set*, fmi2SetFMUstate, fmi2Reset
 * and instantiation. Unchanged since a holder's own write, the instance still holds what the
 * holder wrote, so writing the same values again can be skipped. */
long ssx_fmu_values_epoch(const ssx_fmu *fmu);
/* After fmi2DoStep returned fmi2Discard: whether the FMU asks to end the simulation
 * (fmi2GetBooleanStatus(fmi2Terminated)) and the time it reached (fmi2GetRealStatus(
 * fmi2LastSuccessfulTime)). Each returns the fmi2Status, or -1. */
int ssx_fmu_get_terminated(ssx_fmu *fmu, int *terminated);
int ssx_fmu_get_last_successful_time(ssx_fmu *fmu, double *time);
/* "fmi2OK" ... "fmi2Pending"; for -1 (no status: the engine failed) it says so. */
const char *ssx_fmi2_status_name(int status);
/* The standard's name of a status of this FMU's calls ("fmi3Discard"), as
 * ssx_fmi2_status_name. */
const char *ssx_fmu_status_text(const ssx_fmu *fmu, int status);
/* The standard's name of the call in `slot` (an ssx_fmu_slot: "fmi3DoStep"), "" when the FMU
 * has none. */
const char *ssx_fmu_function_name(const ssx_fmu *fmu, int slot);

/* The name of the variable with value reference vr when the FMU was loaded with its names
 * (FMI 3.0), else "". */
const char *ssx_fmu_variable_name(const ssx_fmu *fmu, unsigned int vr);

/* The last doStep's out-arguments (all 0 before a step). */
void ssx_fmu_step_outcome(const ssx_fmu *fmu, fmu_step_outcome *outcome);

/* The Model Exchange calls of an FMU loaded with SSX_MODEL_EXCHANGE, checked like every other
 * call; each returns the status, or -1. Event mode (enter, new discrete states) serves an
 * FMI 3.0 Co-Simulation instance made with eventModeUsed too, with fmi3EnterStepMode to leave
 * it. */
int ssx_fmu_set_time(ssx_fmu *fmu, double time);
int ssx_fmu_set_continuous_states(ssx_fmu *fmu, const double *x, size_t nx);
int ssx_fmu_get_continuous_states(ssx_fmu *fmu, double *x, size_t nx);
int ssx_fmu_get_derivatives(ssx_fmu *fmu, double *dx, size_t nx);
int ssx_fmu_get_event_indicators(ssx_fmu *fmu, double *z, size_t nz);
int ssx_fmu_get_nominals_of_continuous_states(ssx_fmu *fmu, double *nominals, size_t nx);
int ssx_fmu_enter_event_mode(ssx_fmu *fmu);
int ssx_fmu_new_discrete_states(ssx_fmu *fmu, ssx_fmu_event_info *info);
int ssx_fmu_enter_step_mode(ssx_fmu *fmu);
/* FMI 3.0 in event mode at t: ticks the periodic input clocks due at t */
int ssx_fmu_tick_clocks(ssx_fmu *fmu, double t);
/* The first tick of the FMU's periodic input clocks after t (not at t): a time event of a
 * Model Exchange FMU. INFINITY without clocks or without an instance. */
double ssx_fmu_next_clock_tick(const ssx_fmu *fmu, double t);
/* FMI 3.0 Co-Simulation in event mode: which output clocks tick (active[k], one per output
 * clock of the load spec), and the tick of triggered input clock `clock`. */
int ssx_fmu_read_output_clocks(ssx_fmu *fmu, int *active);
int ssx_fmu_tick_triggered_clock(ssx_fmu *fmu, size_t clock);
/* FMI 3.0 Co-Simulation in Event Mode at t: asks for the countdown clocks' intervals and plans
 * the next tick of each newly announced one. */
int ssx_fmu_plan_clocks(ssx_fmu *fmu, double t);
/* How many output clocks and triggered input clocks the load spec gave (0 for other back-ends). */
void ssx_fmu_clock_counts(const ssx_fmu *fmu, size_t *n_output, size_t *n_triggered);
int ssx_fmu_enter_continuous_time_mode(ssx_fmu *fmu);
int ssx_fmu_completed_integrator_step(ssx_fmu *fmu, int no_set_state_prior,
                                      int *enter_event_mode, int *terminate_simulation);
/* How many continuous states and event indicators the live instance says it has (FMI 3.0
 * Model Exchange: fmi3GetNumberOfContinuousStates/EventIndicators); other FMUs refuse them. */
int ssx_fmu_get_number_of_continuous_states(ssx_fmu *fmu, size_t *n);
int ssx_fmu_get_number_of_event_indicators(ssx_fmu *fmu, size_t *n);
/* The relative tolerance the live instance was set up with (fmi2SetupExperiment): 1 with it
 * in *tolerance, 0 when none was given. */
int ssx_fmu_experiment_tolerance(const ssx_fmu *fmu, double *tolerance);
/* Whether the FMU was loaded for Model Exchange. */
int ssx_fmu_is_model_exchange(const ssx_fmu *fmu);
/* Whether the live instance entered initialization mode and has not been asked to leave it
 * (FMI 1.0: is instantiated, its initializing call not made yet). */
int ssx_fmu_in_initialization_mode(const ssx_fmu *fmu);
/* Whether its standard lets values be read in initialization mode (FMI 1.0 computes them in
 * its initializing call). */
int ssx_fmu_reads_in_initialization_mode(const ssx_fmu *fmu);

/* An isolated FMU's host process (to watch a run's calls), NULL when the binary runs here. */
ssx_remote *ssx_fmu_remote(const ssx_fmu *fmu);

#endif
