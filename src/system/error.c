/* Error reporting of the engine. */
#include "error.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmu_binding.h"

ssx_error *error_record(ssx_system *sys)
{
    const thread_records *own = &sys->thread_records;
    return own->error != NULL ? own->error(own->owner) : &sys->error;
}

ssx_termination *termination_record(ssx_system *sys)
{
    const thread_records *own = &sys->thread_records;
    return own->termination != NULL ? own->termination(own->owner) : &sys->termination;
}

/* Fills the record of the current thread: the system's, or a worker's own while it steps a
 * share of a batch (the calling thread publishes the first one afterwards). */
static ssx_error *vrecord(ssx_system *sys, ssx_error_kind kind, int component, int indicator,
                          double t, const char *format, va_list args)
{
    ssx_error *e = error_record(sys);
    e->kind = kind;
    e->component = component;
    e->indicator = indicator;
    e->output = -1;
    e->time = t;
    e->fmi_status = -1;
    vsnprintf(e->message, sizeof e->message, format, args);
    return e;
}

SSX_PRINTF(6, 7)
static ssx_error *record(ssx_system *sys, ssx_error_kind kind, int component, int indicator,
                         double t, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    ssx_error *e = vrecord(sys, kind, component, indicator, t, format, args);
    va_end(args);
    return e;
}

int fail_kind(ssx_system *sys, ssx_error_kind kind, int component, int indicator, double t,
              const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vrecord(sys, kind, component, indicator, t, format, args);
    va_end(args);
    return -1;
}

int fail_fmi(ssx_system *sys, const ssx_component *c, const ssx_fmu *fmu, double t, int status,
             const char *call)
{
    const char *log = ssx_fmu_last_message(fmu);
    /* no status: the engine refused the call before the FMU saw it, and its message says why */
    ssx_error *e = status < 0
        ? record(sys, SSX_ERROR_FMI, c->index, -1, t, "component '%s': %s refused at t=%.17g: %s",
                 c->name, call, t, log[0] ? log : ssx_fmu_status_text(fmu, status))
        : record(sys, SSX_ERROR_FMI, c->index, -1, t,
                 "component '%s': %s failed at t=%.17g with status %s%s%s%s", c->name, call, t,
                 ssx_fmu_status_text(fmu, status), log[0] ? " (FMU log: " : "", log,
                 log[0] ? ")" : " (the FMU logged no message)");
    e->fmi_status = status;
    return -1;
}

int fail_status(ssx_system *sys, const ssx_component *c, double t, int status,
                const char *format, ...)
{
    va_list args;
    va_start(args, format);
    ssx_error *e = vrecord(sys, SSX_ERROR_SIMULATION, c->index, -1, t, format, args);
    va_end(args);
    e->fmi_status = status;
    return -1;
}

int fail_non_finite(ssx_system *sys, const ssx_component *c, int output, double t)
{
    ssx_error *e = record(sys, SSX_ERROR_NON_FINITE, c->index, -1, t,
                          "component '%s': output %d is %g at t=%.17g (non-finite values stop "
                          "the run unless they are allowed)",
                          c->name, output, c->outputs[output], t);
    e->output = output;
    return -1;
}

int fail_hook(ssx_system *sys, const ssx_component *c, double t, const char *hook)
{
    record(sys, SSX_ERROR_CALLBACK, c->index, -1, t,
           "component '%s': the Python %s hook failed at t=%.17g", c->name, hook, t);
    return -1;
}

void clear_error(ssx_system *sys)
{
    memset(&sys->error, 0, sizeof sys->error);
    sys->error.component = -1;
    sys->error.indicator = -1;
    sys->error.output = -1;
    sys->error.fmi_status = -1;
    sys->error.time = NAN;
}

ssx_component *system_component(ssx_system *sys, int index)
{
    if (index < 0 || index >= sys->n_components) {
        fail_config(sys, -1, -1, sys->time,
                    "unknown component index %d (system '%s' has %d components)", index, sys->name,
                    sys->n_components);
        return NULL;
    }
    return sys->components[index];
}
