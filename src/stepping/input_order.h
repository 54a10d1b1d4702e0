/* What inputs do over a macro step, and how far they are off at its end.
 *
 * Input order 0 holds every input constant over a step. Order 1 or 2 hands each connected Real
 * input of an FMU that declares canInterpolateInputs the first (and second) time derivative of
 * its polynomial over the step: under Gauss-Seidel a driver that already stepped gives an
 * interpolation between its outputs at t and t + h, any other driver an extrapolation from t,
 * with derivatives from the driver's output derivatives where it declares
 * maxOutputDerivativeOrder >= 1, else from the coupling history (the outputs at the last
 * communication points; an event starts it again). Inputs of an FMU that cannot interpolate are
 * held: at their value at t, or (ssx_set_extrapolate_held_inputs) at the mean of the same
 * polynomial over the step. Those of an algebraic loop's members are held at t (the loop is
 * solved at t + h).
 *
 * With a workspace, each coupled step also measures the coupling error: for every connection
 * the difference between the driver's output at t + h and the value the input reached there,
 * weighted by the step control's tolerances (the error-controlled algorithm reads it). */
#ifndef SSX_INPUT_ORDER_H
#define SSX_INPUT_ORDER_H

#include "system.h"

/* Sets up the workspace for the system as built, after coupling_prepare: needed for input
 * order >= 1 or error-controlled steps; it wraps the coupling's step. */
int input_order_prepare(ssx_system *sys);
void input_order_free(ssx_system *sys);
/* The derivatives of c's driven Real inputs over the coming step, after their values are set
 * (coupling_propagate_inputs); may move those values to the polynomial's start. */
void input_order_propagate(ssx_system *sys, ssx_component *c);
/* Writes c's input derivatives to its FMU (fmi2SetRealInputDerivatives); the FMU kind calls it
 * as the system's write_input_derivatives, which input_order_prepare sets. */
int input_order_write(ssx_system *sys, ssx_component *c);
/* The outputs changed at an instant (an event): the coupling history starts again. */
void input_order_forget(ssx_system *sys);
/* Inside a coupled step, after the members of loop group g stepped and before the loop is
 * solved: the error of the loop's inputs (held over the step) against what their drivers
 * produced, and the residuals of the power bonds with an end in the loop, while the solution
 * has not yet made the inputs equal their drivers' outputs. */
void input_order_measure_loop(ssx_system *sys, const ssx_group *g);
/* The weighted coupling error of the last coupled step (0 without a workspace). */
double input_order_error(const ssx_system *sys);

/* What the input motion carries from one communication step to the next (the coupling history,
 * each component's input order), as doubles for a saved state: how many (0 without a
 * workspace), and copies out and back into the same system. */
size_t input_order_state_size(const ssx_system *sys);
void input_order_state_save(const ssx_system *sys, double *values);
void input_order_state_restore(ssx_system *sys, const double *values);

#endif
