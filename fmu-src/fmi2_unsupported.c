/* Functions this FMU exports but does not support: input and output derivatives. Each returns
 * fmi2Error with a message. */
#include "fmu_instance.h"
#include "fmu_log.h"

static fmi2Status unsupported(fmi2Component c, const char *function)
{
    fmu_instance *inst = c;
    if (inst == NULL)
        return fmi2Error;
    return fmu_error(inst, "%s is not supported by this FMU", function);
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2SetRealInputDerivatives");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives");
}
