/* What a call of the version-neutral core reports. Each FMI version's entry points convert it
 * to their standard's status at their boundary (fmi1_status, fmi2_status, fmi3_status), so the
 * core knows no standard's types. */
#ifndef SYSSIMX_FMU_STATUS_H
#define SYSSIMX_FMU_STATUS_H

typedef enum {
    FMU_OK,
    FMU_WARNING,
    FMU_DISCARD, /* the call could not be completed; the instance stays as it was */
    FMU_ERROR,   /* the call failed; the instance may be used again */
    FMU_FATAL    /* the instance is broken for good: no call is allowed any more */
} fmu_status;

#endif
