/* Higher-order inputs and output derivatives for every interface.
 *
 * Inputs: an importer may give the first and second time derivatives of Real inputs
 * (fmi2SetRealInputDerivatives); a step then drives each such input along its Taylor polynomial
 * from the communication point, and after the step the polynomial goes on from the step's end
 * (the value at the end becomes the input, the first derivative follows the second) until the
 * importer sets new derivatives. FMI 3.0 has no input derivatives: there the importer answers an
 * intermediate update callback with the input values at the time the FMU asks for
 * (intermediate_update below).
 *
 * Outputs: the first time derivative of an output at the current point, along the trajectory
 * (the states move with their derivatives, the inputs with their derivatives, time with time),
 * computed from the model's equations by a central difference of the output function. */
#ifndef SYSSIMX_FMU_INTERPOLATION_H
#define SYSSIMX_FMU_INTERPOLATION_H

#include "fmu_instance.h"

/* The highest input derivative order accepted and the output derivative order served (declared
 * as maxOutputDerivativeOrder). */
#define FMU_MAX_INPUT_DERIVATIVE_ORDER 2
#define FMU_MAX_OUTPUT_DERIVATIVE_ORDER 1

/* Stores derivative order[i] of input vr[i]; `function` names the call in messages. */
fmu_status fmu_set_input_derivatives(fmu_instance *inst, const char *function,
                                     const unsigned int vr[], size_t nvr,
                                     const int order[], const double value[]);
/* Derivative order[i] of output vr[i] at the instance's time into value[i]. */
fmu_status fmu_get_output_derivatives(fmu_instance *inst, const char *function,
                                      const unsigned int vr[], size_t nvr,
                                      const int order[], double value[]);

/* Called by fmu_do_step around the back-end's integration from t to t_end. */
void fmu_inputs_begin_step(fmu_instance *inst);
void fmu_inputs_end_step(fmu_instance *inst, double t_end);

#endif
