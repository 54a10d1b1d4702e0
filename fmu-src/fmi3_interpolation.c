/* fmi3GetOutputDerivatives over fmu_interpolation.h (maxOutputDerivativeOrder). FMI 3.0 has no
 * input derivatives: inputs move inside a step through intermediate update
 * (fmi3_lifecycle.c). */
#include "fmi3_instance.h"
#include "fmu_interpolation.h"
#include "fmu_log.h"

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int32 orders[],
                                    fmi3Float64 values[], size_t nValues)
{
    fmi3_instance *self = fmi3_checked(instance, "fmi3GetOutputDerivatives", MODE_BIT(MODE_STEP));
    if (self == NULL)
        return fmi3Error;
    if (nValues != nValueReferences)
        return fmi3_status(fmu_error(&self->core,
                                     "fmi3GetOutputDerivatives: %zu values for %zu value "
                                     "references",
                                     nValues, nValueReferences));
    return fmi3_status(fmu_get_output_derivatives(&self->core, "fmi3GetOutputDerivatives",
                                                  valueReferences, nValueReferences, orders,
                                                  values));
}
