/* An FMI 1.0 Co-Simulation FMU whose fmiDoStep never returns once the time reaches 0.5 (it
 * sleeps in a loop), for tests/python/test_run_interruptible.py (modelDescription.xml beside
 * it): y = time until then. Only a host process that is killed ends such a step. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <time.h>

#include "fmi1Functions.h"

#define EXPORT(type, name) __attribute__((visibility("default"))) type fmi1_stuck_##name

enum { VR_Y };

static const double STUCK_FROM = 0.5;

typedef struct {
    double time;
} slave;

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
    (void)name, (void)guid, (void)location, (void)mime_type, (void)timeout, (void)visible,
        (void)interactive, (void)functions, (void)logging_on;
    return calloc(1, sizeof(slave));
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
    if (t >= STUCK_FROM) {
        const struct timespec pause = {.tv_sec = 0, .tv_nsec = 10000000};
        for (;;) {
            nanosleep(&pause, NULL);
        }
    }
    ((slave *)c)->time = t + step;
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
