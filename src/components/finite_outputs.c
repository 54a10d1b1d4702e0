/* Finite outputs (see finite_outputs.h). */
#include "finite_outputs.h"

#include <math.h>

#include "error.h"
#include "system.h"

int component_check_outputs(ssx_system *sys, const ssx_component *c, double t)
{
    if (sys->allow_non_finite) {
        return 0;
    }
    for (int i = 0; i < c->n_outputs; ++i) {
        if (!isfinite(c->outputs[i])) {
            return fail_non_finite(sys, c, i, t);
        }
    }
    return 0;
}
