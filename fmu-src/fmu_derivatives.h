/* Directional derivatives of outputs with respect to inputs, states held fixed, for every
 * interface; `function` names the call in messages. */
#ifndef SYSSIMX_FMU_DERIVATIVES_H
#define SYSSIMX_FMU_DERIVATIVES_H

#include <stddef.h>

#include "fmu_instance.h"

fmu_status fmu_directional_derivative(fmu_instance *inst, const char *function,
                                      const unsigned int vUnknown_ref[], size_t nUnknown,
                                      const unsigned int vKnown_ref[], size_t nKnown,
                                      const double dvKnown[], double dvUnknown[]);

#endif
