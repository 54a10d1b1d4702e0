/* fmi3GetDirectionalDerivative: outputs with respect to inputs, states held fixed, in every
 * state after instantiation. */
#include "fmi3_allowed.h"
#include "fmi3_instance.h"
#include "fmu_derivatives.h"
#include "fmu_log.h"

#define FUNCTION "fmi3GetDirectionalDerivative"

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                        size_t nUnknowns, const fmi3ValueReference knowns[],
                                        size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                        fmi3Float64 sensitivity[], size_t nSensitivity)
{
    fmi3_instance *inst = fmi3_checked(instance, FMI3_CALL(fmi3GetDirectionalDerivative));
    if (inst == NULL)
        return fmi3Error;
    if (nSeed != nKnowns || nSensitivity != nUnknowns)
        return fmi3_status(fmu_error(&inst->core,
                                     FUNCTION ": %zu seeds for %zu knowns or %zu sensitivities "
                                              "for %zu unknowns (the variables are scalars)",
                                     nSeed, nKnowns, nSensitivity, nUnknowns));
    return fmi3_status(fmu_directional_derivative(&inst->core, FUNCTION, unknowns, nUnknowns,
                                                  knowns, nKnowns, seed, sensitivity));
}
