/* A hostile FMI 2.0 Co-Simulation FMU for the isolation tests: y = time, until the first
 * doStep that ends after fail_time, which misbehaves as the parameter `mode` says:
 *   0 behaves, 1 segfaults, 2 aborts, 3 calls _exit(3), 4 never returns (a busy loop),
 *   5 logs the format "%s%s%n" without its arguments and returns fmi2Error,
 *   6 forks a child that lives on (it waits for signals; its process id goes to the file
 *     named by SYSSIMX_TEST_CHILD_PID_FILE) and goes on behaving, once,
 *   7 logs naming the environments 1 and 2, not the one it was given (as some exported FMUs
 *     do), and goes on behaving.
 * Written against the FMI 2.0 API directly (not the framework of fmu-src/): the framework
 * never calls the logger with a bad format, and that is the point here. */
#define _DEFAULT_SOURCE /* fork, pause */
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#include "fmi2Functions.h"

enum { VR_Y, VR_MODE, VR_FAIL_TIME };
enum { BEHAVE, SEGFAULT, ABORT, EXIT, ENDLESS_LOOP, BAD_LOG_FORMAT, FORK_CHILD, FOREIGN_ENVIRONMENT };

typedef struct {
    double time;
    int mode;
    double fail_time;
    fmi2CallbackFunctions callbacks;
    char name[64];
} hostile;

typedef struct {
    double time;
} hostile_state;

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
    hostile *h = calloc(1, sizeof *h);
    if (h != NULL) {
        h->fail_time = 0.5;
        h->callbacks = *callbacks;
        strncpy(h->name, name != NULL ? name : "", sizeof h->name - 1);
    }
    return h;
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
    ((hostile *)c)->time = start;
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
    const hostile *h = c;
    for (size_t i = 0; i < n; ++i) {
        values[i] = vr[i] == VR_Y ? h->time : vr[i] == VR_FAIL_TIME ? h->fail_time : 0.0;
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                       const fmi2Real values[])
{
    hostile *h = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] != VR_FAIL_TIME) {
            return fmi2Error;
        }
        h->fail_time = values[i];
    }
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          fmi2Integer values[])
{
    const hostile *h = c;
    for (size_t i = 0; i < n; ++i) {
        values[i] = vr[i] == VR_MODE ? h->mode : 0;
    }
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                          const fmi2Integer values[])
{
    hostile *h = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] != VR_MODE) {
            return fmi2Error;
        }
        h->mode = values[i];
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

/* A child that outlives the FMU unless someone ends it. */
static void fork_child(void)
{
    pid_t child = fork();
    if (child != 0) {
        return;
    }
    const char *pid_file = getenv("SYSSIMX_TEST_CHILD_PID_FILE");
    FILE *out = pid_file != NULL ? fopen(pid_file, "w") : NULL;
    if (out != NULL) {
        fprintf(out, "%d\n", (int)getpid());
        fclose(out);
    }
    for (;;) {
        pause();
    }
}

static void misbehave(hostile *h)
{
    switch (h->mode) {
    case FORK_CHILD:
        fork_child();
        h->mode = BEHAVE;
        break;
    case SEGFAULT: {
        volatile int *volatile target = NULL; /* volatile: no trap, no dropped store */
        *target = 1;
        break;
    }
    case ABORT:
        abort();
    case EXIT:
        _exit(3);
    case ENDLESS_LOOP:
        for (volatile int spin = 1; spin;) {
        }
        break;
    case FOREIGN_ENVIRONMENT:
        h->callbacks.logger((fmi2ComponentEnvironment)1, h->name, fmi2OK, "logAll",
                            "naming environment 1");
        h->callbacks.logger((fmi2ComponentEnvironment)2, h->name, fmi2OK, "logAll",
                            "naming environment 2 at t=%g", h->time);
        break;
    default:
        break;
    }
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real step, fmi2Boolean no_set_prior)
{
    (void)no_set_prior;
    hostile *h = c;
    if (t + step > h->fail_time && h->mode == BAD_LOG_FORMAT) {
        /* deliberately no arguments for the conversions */
        h->callbacks.logger(h->callbacks.componentEnvironment, h->name, fmi2Error,
                            "logStatusError", "%s%s%n");
        return fmi2Error;
    }
    if (t + step > h->fail_time) {
        misbehave(h);
    }
    h->time = t + step;
    return fmi2OK;
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    const hostile *h = c;
    if (*state == NULL) {
        *state = malloc(sizeof(hostile_state));
        if (*state == NULL) {
            return fmi2Error;
        }
    }
    ((hostile_state *)*state)->time = h->time;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state)
{
    ((hostile *)c)->time = ((const hostile_state *)state)->time;
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    (void)c;
    free(*state);
    *state = NULL;
    return fmi2OK;
}
