/* The core's status as FMI 2.0's: the boundary every fmi2 entry point returns through. */
#ifndef SYSSIMX_FMI2_STATUS_H
#define SYSSIMX_FMI2_STATUS_H

#include "fmi2Functions.h"
#include "fmu_status.h"

static inline fmi2Status fmi2_status(fmu_status status)
{
    switch (status) {
    case FMU_OK: return fmi2OK;
    case FMU_WARNING: return fmi2Warning;
    case FMU_DISCARD: return fmi2Discard;
    case FMU_ERROR: break;
    case FMU_FATAL: return fmi2Fatal;
    }
    return fmi2Error;
}

#endif
