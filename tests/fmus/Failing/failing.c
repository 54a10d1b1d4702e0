/* Failing.mo: y = u, and after fail_time the FMU fails in the way `failure` chooses. It lets
 * masters test how they report a failing FMU:
 *   0  fmi2DoStep returns fmi2Error (with a log message) for a step that ends after fail_time
 *   1  fmi2DoStep returns fmi2Fatal: the instance accepts no further call
 *   2  fmi2DoStep returns fmi2Discard without asking to terminate (stays at the step's start)
 *   3  every fmi2Get* fails once the FMU's time is past fail_time
 *   4  y becomes NaN past fail_time */
#include <math.h>

#include "model.h"

enum { VR_Y, VR_U, VR_FAIL_TIME, VR_FAILURE, VARIABLE_COUNT };
enum { FAIL_ERROR, FAIL_FATAL, FAIL_DISCARD, FAIL_READ, FAIL_NAN };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_Y, "y", NULL, "copy of the input", DEPENDS(VR_U), DEPENDS(VR_U)),
    REAL_INPUT(VR_U, "u", NULL, 0, "input"),
    REAL_PARAMETER(VR_FAIL_TIME, "fail_time", "s", 1, "the FMU fails after this time"),
    INTEGER_PARAMETER(VR_FAILURE, "failure", FAIL_ERROR,
                      "0 doStep error, 1 doStep fatal, 2 doStep discard, 3 fmi2Get error, "
                      "4 NaN output"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)x;
    int nan_now = (int)v[VR_FAILURE] == FAIL_NAN && t > v[VR_FAIL_TIME];
    v[VR_Y] = nan_now ? NAN : v[VR_U];
}

static const char *step_refusal(const double *v, double t_end, step_refusal_kind *kind)
{
    int failure = (int)v[VR_FAILURE];
    if (t_end <= v[VR_FAIL_TIME] || failure > FAIL_DISCARD) {
        return NULL;
    }
    if (failure == FAIL_FATAL) {
        *kind = STEP_FATAL;
        return "the simulation passed fail_time (a deliberate fatal failure)";
    }
    if (failure == FAIL_DISCARD) {
        *kind = STEP_DISCARDED;
        return "the simulation passed fail_time (a deliberate discard)";
    }
    return "the simulation passed fail_time (a deliberate failure)";
}

static const char *read_refusal(const double *v, double t)
{
    return (int)v[VR_FAILURE] == FAIL_READ && t > v[VR_FAIL_TIME]
               ? "the simulation passed fail_time (a deliberate read failure)"
               : NULL;
}

const model_definition fmu_model = {
    .name = "Failing",
    .description = "Copies its input and fails after fail_time (Failing.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
    .step_refusal = step_refusal,
    .read_refusal = read_refusal,
};
