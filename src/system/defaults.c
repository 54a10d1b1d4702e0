/* The engine's defaults: one place for every option a system starts with. */
#include "syssimx_engine.h"

void ssx_get_defaults(ssx_defaults *out)
{
    *out = (ssx_defaults){.coupling = SSX_GAUSS_SEIDEL,
                          .loop_tolerance = 1e-10,
                          .loop_max_iterations = 100,
                          .loop_damping = 1.0,
                          .loop_jacobian = SSX_JACOBIAN_AUTO,
                          .tol_time = 1e-9,
                          .tol_value = 1e-9,
                          .max_iterations = 100,
                          .max_microsteps = 10,
                          .locator = SSX_ILLINOIS,
                          .zeno_min_interval = 0.0,
                          .output_interval = 1,
                          .model_exchange_tolerance = 1e-5,
                          .threads = 1,
                          .input_order = 0,
                          .extrapolate_held_inputs = 0,
                          .step_rtol = 1e-4,
                          .step_atol = 1e-4,
                          .step_min = 1e-9,
                          .step_safety = 0.9,
                          .step_min_change = 0.2,
                          .step_max_change = 5.0,
                          .step_proportional_gain = 0.2,
                          .step_integral_gain = 0.15};
}
