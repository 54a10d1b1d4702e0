/* Directional derivatives of outputs with respect to inputs, states held fixed, for every
 * interface; `function` names the call in messages. */
#ifndef SYSSIMX_FMU_DERIVATIVES_H
#define SYSSIMX_FMU_DERIVATIVES_H

#include <stddef.h>

#include "fmu_instance.h"

fmi2Status fmu_directional_derivative(fmu_instance *inst, const char *function,
                                      const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                      const fmi2ValueReference vKnown_ref[], size_t nKnown,
                                      const double dvKnown[], double dvUnknown[]);

#endif
