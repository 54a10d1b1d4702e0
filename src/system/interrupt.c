#include "interrupt.h"

#include "error.h"
#include "monitor.h"

int run_interrupted(ssx_system *sys, double t)
{
    if (!sys->monitor.running || sys->thread_records.error != NULL ||
        monitor_after_step(&sys->monitor, t) == 0) {
        return 0;
    }
    return fail_kind(sys, SSX_ERROR_CALLBACK, -1, -1, t,
                     "system '%s': the run was stopped by its monitor at t=%.17g", sys->name, t);
}
