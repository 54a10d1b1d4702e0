/* Filling ssx_error: every failure names what failed, where and when. All return -1. */
#ifndef SSX_ERROR_H
#define SSX_ERROR_H

#include "component.h"
#include "system.h"

#if defined(__GNUC__)
#define SSX_PRINTF(fmt, args) __attribute__((format(printf, fmt, args)))
#else
#define SSX_PRINTF(fmt, args)
#endif

/* A failure of kind `kind`; component/indicator may be -1, t may be NAN. The macros name the
 * common kinds: they differ in the kind alone, so they are this one call. */
int fail_kind(ssx_system *sys, ssx_error_kind kind, int component, int indicator, double t,
              const char *format, ...) SSX_PRINTF(6, 7);
/* A failure while running. fail(sys, component, indicator, t, format, ...) */
#define fail(sys, ...) fail_kind((sys), SSX_ERROR_SIMULATION, __VA_ARGS__)
/* Bad input: a call's arguments, or a call the system's state does not allow. */
#define fail_config(sys, ...) fail_kind((sys), SSX_ERROR_CONFIG, __VA_ARGS__)
/* Chattering / too many micro steps. */
#define fail_zeno(sys, ...) fail_kind((sys), SSX_ERROR_ZENO, __VA_ARGS__)
/* A call of component c's FMU `fmu` returned `status` (or the binding failed, status -1). */
int fail_fmi(ssx_system *sys, const ssx_component *c, const ssx_fmu *fmu, double t, int status,
             const char *call);
/* Component c failed in a way an fmi2 status explains without an fmi2 call failing (a step
 * discarded without a request to terminate): kind SSX_ERROR_SIMULATION with that status. */
int fail_status(ssx_system *sys, const ssx_component *c, double t, int status,
                const char *format, ...) SSX_PRINTF(5, 6);
/* Output `output` of component c holds a NaN or an infinity at time t. */
int fail_non_finite(ssx_system *sys, const ssx_component *c, int output, double t);
/* A Python hook of component c reported failure; Python keeps the exception. */
int fail_hook(ssx_system *sys, const ssx_component *c, double t, const char *hook);
void clear_error(ssx_system *sys);
/* The component of that index, or NULL with a configuration error naming the index (every
 * public call that takes a component index asks here). */
ssx_component *system_component(ssx_system *sys, int index);
/* What the current thread fills when a component fails or asks to stop: its own record while
 * it steps a share of a batch, else the system's. */
ssx_error *error_record(ssx_system *sys);
ssx_termination *termination_record(ssx_system *sys);
/* fmi2OK and fmi2Warning let the simulation go on. Inline: checked after every fmi2 call. */
static inline int fmi_ok(int status)
{
    return status == 0 || status == 1;
}

#endif
