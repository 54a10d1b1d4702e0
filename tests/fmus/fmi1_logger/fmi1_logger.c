/* An FMI 1.0 Co-Simulation FMU that misuses its logger as some exported FMUs do, for
 * tests/python/test_fmu_loggers.py (modelDescription.xml beside it): y = time, and
 *   - fmiInstantiateSlave logs, naming no component, a format with conversions and no
 *     arguments (the FMU's text, formatted already, handed over as the format);
 *   - every fmiDoStep logs naming component 1, not its own, with such a format again.
 * Written against the FMI 1.0 API directly: the FMU framework of fmu-src/ never misuses the
 * logger, and that is the point here. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fmi1Functions.h"

#define EXPORT(type, name) __attribute__((visibility("default"))) type fmi1_logger_##name

enum { VR_Y };

typedef struct {
    double time;
    fmi1CallbackLogger log;
    char name[64];
} slave;

/* The format asks for more arguments than any register holds: the missing ones are read from
 * the caller's stack, which this frame fills with an address no string lies at, so that an
 * importer reading them as strings faults every time, not by chance. */
static __attribute__((noinline)) void log_without_arguments(fmi1CallbackLogger log,
                                                             fmi1Component component,
                                                             const char *name,
                                                             const char *format)
{
    volatile uintptr_t unmapped[64];
    for (size_t i = 0; i < sizeof unmapped / sizeof unmapped[0]; ++i) {
        unmapped[i] = 16;
    }
    log(component, name, fmi1OK, "log", format);
    (void)unmapped[0];
}

#define NO_ARGUMENTS_FORMAT                                                                   \
    "at %d %s%s%s%s%s%s%s%s%s%s%s%s%s%s%s and %f" /* deliberately without the arguments */

EXPORT(const char *, fmiGetTypesPlatform)(void)
{
    return "standard32";
}

EXPORT(const char *, fmiGetVersion)(void)
{
    return "1.0";
}

EXPORT(fmi1Component, fmiInstantiateSlave)(fmi1String name, fmi1String guid,
                                            fmi1String location, fmi1String mime_type,
                                            fmi1Real timeout, fmi1Boolean visible,
                                            fmi1Boolean interactive,
                                            fmi1CallbackFunctions functions,
                                            fmi1Boolean logging_on)
{
    (void)guid, (void)location, (void)mime_type, (void)timeout, (void)visible,
        (void)interactive, (void)logging_on;
    slave *s = calloc(1, sizeof *s);
    if (s == NULL) {
        return NULL;
    }
    s->log = functions.logger;
    strncpy(s->name, name != NULL ? name : "", sizeof s->name - 1);
    if (s->log != NULL) {
        log_without_arguments(s->log, NULL, s->name, "instantiated " NO_ARGUMENTS_FORMAT);
    }
    return s;
}

EXPORT(void, fmiFreeSlaveInstance)(fmi1Component c)
{
    free(c);
}

EXPORT(fmi1Status, fmiInitializeSlave)(fmi1Component c, fmi1Real start, fmi1Boolean stop_defined,
                                       fmi1Real stop)
{
    (void)stop_defined, (void)stop;
    ((slave *)c)->time = start;
    return fmi1OK;
}

EXPORT(fmi1Status, fmiTerminateSlave)(fmi1Component c)
{
    (void)c;
    return fmi1OK;
}

EXPORT(fmi1Status, fmiResetSlave)(fmi1Component c)
{
    ((slave *)c)->time = 0.0;
    return fmi1OK;
}

EXPORT(fmi1Status, fmiSetDebugLogging)(fmi1Component c, fmi1Boolean logging_on)
{
    (void)c, (void)logging_on;
    return fmi1OK;
}

EXPORT(fmi1Status, fmiDoStep)(fmi1Component c, fmi1Real t, fmi1Real step, fmi1Boolean new_step)
{
    (void)new_step;
    slave *s = c;
    if (s->log != NULL) {
        /* a component that is not this FMU's: the importer must not read through it */
        log_without_arguments(s->log, (fmi1Component)1, s->name, "stepped " NO_ARGUMENTS_FORMAT);
    }
    s->time = t + step;
    return fmi1OK;
}

EXPORT(fmi1Status, fmiGetReal)(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                               fmi1Real values[])
{
    const slave *s = c;
    for (size_t i = 0; i < n; ++i) {
        if (vr[i] != VR_Y) {
            return fmi1Error;
        }
        values[i] = s->time;
    }
    return fmi1OK;
}

EXPORT(fmi1Status, fmiSetReal)(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                               const fmi1Real values[])
{
    (void)c, (void)vr, (void)values;
    return n == 0 ? fmi1OK : fmi1Error;
}

EXPORT(fmi1Status, fmiGetInteger)(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                  fmi1Integer values[])
{
    (void)c, (void)vr, (void)values;
    return n == 0 ? fmi1OK : fmi1Error;
}

EXPORT(fmi1Status, fmiSetInteger)(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                  const fmi1Integer values[])
{
    (void)c, (void)vr, (void)values;
    return n == 0 ? fmi1OK : fmi1Error;
}

EXPORT(fmi1Status, fmiGetBoolean)(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                  fmi1Boolean values[])
{
    (void)c, (void)vr, (void)values;
    return n == 0 ? fmi1OK : fmi1Error;
}

EXPORT(fmi1Status, fmiSetBoolean)(fmi1Component c, const fmi1ValueReference vr[], size_t n,
                                  const fmi1Boolean values[])
{
    (void)c, (void)vr, (void)values;
    return n == 0 ? fmi1OK : fmi1Error;
}
