/* KeepDefaults.mo: an FMU whose declared starts are rounded prints of its own values, as some
 * exporters write them with %f (libcosim's quarter_truck Wheel.fmu: two step-size controls).
 * The model holds h_min = u = 1e-7; modelDescription.xml says "0.000000" for both. A master
 * that writes declared starts sets h_min to 0, which refuses every step, and u to 0. A master
 * that writes only what the user set sees y = u / h_min = 1. */
#include "model.h"

enum { VR_Y, VR_U, VR_H_MIN, VARIABLE_COUNT };

static const model_variable variables[VARIABLE_COUNT] = {
    REAL_OUTPUT(VR_Y, "y", NULL, "u / h_min (1 with the model's own values)", DEPENDS(VR_U),
                DEPENDS(VR_U, VR_H_MIN)),
    REAL_INPUT_DECLARED(VR_U, "u", NULL, 1e-7, "0.000000",
                        "input, declared start rounded to 0.000000"),
    REAL_PARAMETER_DECLARED(VR_H_MIN, "h_min", NULL, 1e-7, "0.000000",
                            "smallest internal step, declared start rounded to 0.000000"),
};

static void outputs(double *v, double t, const double *x)
{
    (void)t;
    (void)x;
    v[VR_Y] = v[VR_H_MIN] > 0.0 ? v[VR_U] / v[VR_H_MIN] : 0.0;
}

static const char *step_refusal(const double *v, double t_end, step_refusal_kind *kind)
{
    (void)t_end;
    (void)kind; /* a refused step fails (fmi2Error), the default */
    return v[VR_H_MIN] > 0.0 ? NULL : "h_min must be positive: no internal step can finish";
}

const model_definition fmu_model = {
    .name = "KeepDefaults",
    .description = "Declared starts are rounded prints of the model's values (KeepDefaults.mo)",
    .variables = variables,
    .n_variables = VARIABLE_COUNT,
    .default_stop_time = 1.0,
    .default_step_size = 1e-3,
    .outputs = outputs,
    .step_refusal = step_refusal,
};
