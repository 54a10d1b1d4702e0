/* A hand-written FMI 2.0 Co-Simulation FMU whose input and output derivatives are limited,
 * as some exported FMUs' are: y' = u, the input u interpolated over each step by the
 * derivatives the master gives.
 *   max_input_order: fmi2SetRealInputDerivatives returns fmi2Error for any order above it
 *     (and keeps nothing of that call), as FMUs that take first derivatives only do;
 *   nan_output_derivatives = 1: fmi2GetRealOutputDerivatives tells NaN.
 * Written against the FMI 2.0 API directly (not the framework of fmu-src/, which takes every
 * order it declares and always tells finite derivatives). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

enum { VR_U, VR_Y, VR_MAX_INPUT_ORDER, VR_NAN_OUTPUT_DERIVATIVES };

typedef struct {
    double time;
    double u;
    double y;
    double du[2]; /* the input's first and second time derivative over the coming step */
} integrator_state;

typedef struct {
    integrator_state now;
    int max_input_order;
    int nan_output_derivatives;
    fmi2CallbackFunctions callbacks;
    char name[64];
} integrator;

static void log_error(const integrator *fmu, const char *message)
{
    if (fmu->callbacks.logger != NULL) {
        fmu->callbacks.logger(fmu->callbacks.componentEnvironment, fmu->name, fmi2Error,
                              "logStatusError", message); /* no conversions in it */
    }
}

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                              fmi2String resources, const fmi2CallbackFunctions *callbacks,
                              fmi2Boolean visible, fmi2Boolean logging_on)
{
    (void)guid;
    (void)resources;
    (void)visible;
    (void)logging_on;
    if (type != fmi2CoSimulation || callbacks == NULL) {
        return NULL;
    }
    integrator *fmu = calloc(1, sizeof *fmu);
    if (fmu != NULL) {
        fmu->now.u = 1.0;
        fmu->max_input_order = 2;
        fmu->callbacks = *callbacks;
        strncpy(fmu->name, name != NULL ? name : "", sizeof fmu->name - 1);
    }
    return fmu;
}

void fmi2FreeInstance(fmi2Component c)
{
    free(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tolerance_defined,
                               fmi2Real tolerance, fmi2Real start, fmi2Boolean stop_defined,
                               fmi2Real stop)
{
    (void)tolerance_defined;
    (void)tolerance;
    (void)stop_defined;
    (void)stop;
    ((integrator *)c)->now.time = start;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    (void)c;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    (void)c;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    (void)c;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    (void)c;
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                       fmi2Real values[])
{
    const integrator *fmu = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] == VR_U) {
            values[i] = fmu->now.u;
        } else if (vr[i] == VR_Y) {
            values[i] = fmu->now.y;
        } else {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                       const fmi2Real values[])
{
    integrator *fmu = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] == VR_U) {
            fmu->now.u = values[i];
        } else if (vr[i] == VR_Y) {
            fmu->now.y = values[i];
        } else {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          fmi2Integer values[])
{
    const integrator *fmu = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] == VR_MAX_INPUT_ORDER) {
            values[i] = fmu->max_input_order;
        } else if (vr[i] == VR_NAN_OUTPUT_DERIVATIVES) {
            values[i] = fmu->nan_output_derivatives;
        } else {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Integer values[])
{
    integrator *fmu = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] == VR_MAX_INPUT_ORDER) {
            fmu->max_input_order = values[i];
        } else if (vr[i] == VR_NAN_OUTPUT_DERIVATIVES) {
            fmu->nan_output_derivatives = values[i];
        } else {
            return fmi2Error;
        }
    }
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          fmi2Boolean values[])
{
    (void)c;
    (void)vr;
    (void)values;
    return n == 0 ? fmi2OK : fmi2Error;
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Boolean values[])
{
    (void)c;
    (void)vr;
    (void)values;
    return n == 0 ? fmi2OK : fmi2Error;
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                       size_t n, const fmi2Integer order[],
                                       const fmi2Real values[])
{
    integrator *fmu = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] != VR_U || order[i] < 1 || order[i] > fmu->max_input_order) {
            log_error(fmu, "fmi2SetRealInputDerivatives: this order is not supported");
            return fmi2Error;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        fmu->now.du[order[i] - 1] = values[i];
    }
    return fmi2OK;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                        size_t n, const fmi2Integer order[], fmi2Real values[])
{
    const integrator *fmu = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] != VR_Y || order[i] != 1) {
            return fmi2Error;
        }
        values[i] = fmu->nan_output_derivatives ? NAN : fmu->now.u;
    }
    return fmi2OK;
}

/* y gains the integral of u's polynomial over the step; u and its slope move to the step's
 * end, where the polynomial goes on. */
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real step, fmi2Boolean no_set_prior)
{
    (void)no_set_prior;
    integrator *fmu = c;
    integrator_state *s = &fmu->now;
    s->y += step * (s->u + step * (s->du[0] / 2.0 + step * s->du[1] / 6.0));
    s->u += step * (s->du[0] + step * s->du[1] / 2.0);
    s->du[0] += step * s->du[1];
    s->time = t + step;
    return fmi2OK;
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    if (*state == NULL) {
        *state = malloc(sizeof(integrator_state));
        if (*state == NULL) {
            return fmi2Error;
        }
    }
    *(integrator_state *)*state = ((const integrator *)c)->now;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state)
{
    ((integrator *)c)->now = *(const integrator_state *)state;
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    (void)c;
    free(*state);
    *state = NULL;
    return fmi2OK;
}
