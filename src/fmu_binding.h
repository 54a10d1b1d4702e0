/* Internal helpers of the FMU binding that the engine needs beyond the public ssx_fmu_* calls. */
#ifndef SSX_FMU_BINDING_H
#define SSX_FMU_BINDING_H

#include "syssimx_engine.h"

/* Counts instantiations: FMU states of an earlier instance are invalid (the binding frees them
 * when their instance goes away), so a holder compares generations before reusing a state. */
long ssx_fmu_generation(const ssx_fmu *fmu);
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
/* The host process of an isolated FMU, NULL for one loaded into this process. */
struct ssx_remote;
struct ssx_remote *ssx_fmu_remote(const ssx_fmu *fmu);

#endif
