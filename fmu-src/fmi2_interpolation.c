/* Input and output derivatives (canInterpolateInputs, maxOutputDerivativeOrder): the entry
 * points over fmu_interpolation.h. */
#include "fmi2_status.h"
#include "fmu_instance.h"
#include "fmu_interpolation.h"

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    fmu_instance *inst = fmu_checked(c, "fmi2SetRealInputDerivatives", PHASES_SETTABLE);
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_set_input_derivatives(inst, "fmi2SetRealInputDerivatives", vr, nvr,
                                                 order, value));
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[], fmi2Real value[])
{
    fmu_instance *inst = fmu_checked(c, "fmi2GetRealOutputDerivatives", PHASES_STATUS);
    if (inst == NULL)
        return fmi2Error;
    return fmi2_status(fmu_get_output_derivatives(inst, "fmi2GetRealOutputDerivatives", vr, nvr,
                                                  order, value));
}
