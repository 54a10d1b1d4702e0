/* LateNaN.mo: a ramp y = t beside an output that turns NaN at nan_time, as libcosim's 20-sim
 * KnuckleBoomCrane does in Act_Limits[1] from t = 2.048. A master stops or goes on depending on
 * whether the NaN reaches anything. */
#include <math.h>

#include "model.h"

enum { VR_Y, VR_LIMIT, VR_NAN_TIME, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_Y, "y", NULL, "the ramp y = t", DEPENDS_NONE, DEPENDS_NONE),
    REAL_OUTPUT(VR_LIMIT, "limit", NULL, "1, NaN from nan_time on", DEPENDS_NONE,
                DEPENDS(VR_NAN_TIME)),
    REAL_PARAMETER(VR_NAN_TIME, "nan_time", "s", 0.5, "limit is NaN from this time on"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)x;
    v[VR_Y] = t;
    v[VR_LIMIT] = t >= v[VR_NAN_TIME] ? NAN : 1.0;
}

const model_definition fmu_model = {
    .name = "LateNaN",
    .description = "A ramp and an output that turns NaN at nan_time (LateNaN.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 0.1,
    .outputs = outputs,
};
