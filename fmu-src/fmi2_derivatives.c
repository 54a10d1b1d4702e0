/* fmi2GetDirectionalDerivative, in initialization and step mode. */
#include "fmi2_allowed.h"
#include "fmu_derivatives.h"
#include "fmu_instance.h"

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    fmu_instance *inst = fmu_checked(c, FMI2_CALL(fmi2GetDirectionalDerivative));
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_directional_derivative(inst, "fmi2GetDirectionalDerivative",
                                                  vUnknown_ref, nUnknown, vKnown_ref, nKnown,
                                                  dvKnown, dvUnknown));
}
