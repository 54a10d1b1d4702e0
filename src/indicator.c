/* Indicator evaluation and crossing detection. */
#include "indicator.h"

#include <math.h>

#include "error.h"

int indicators_evaluate(ssx_system *sys, double t)
{
    for (int i = 0; i < sys->n_indicators; ++i) {
        ssx_indicator *ind = &sys->indicators[i];
        const ssx_component *c = sys->components[ind->component];
        double value;
        if (ind->output >= 0) {
            value = c->outputs[ind->output];
        } else if (ind->evaluate(ind->user, t, &value) != 0) {
            fail(sys, ind->component, i, t,
                 "component '%s': the Python function of indicator %d failed at t=%.17g", c->name,
                 i, t);
            sys->error.in_callback = 1;
            return -1;
        }
        if (!isfinite(value)) {
            return fail(sys, ind->component, i, t,
                        "component '%s': indicator %d is not finite (%g) at t=%.17g", c->name, i,
                        value, t);
        }
        ind->value = value;
    }
    return 0;
}

int indicator_crossing(const ssx_indicator *ind, double z)
{
    if (ind->on_zero) {
        return 0;
    }
    if (ind->sign > 0 && z <= 0.0) {
        return -1;
    }
    if (ind->sign < 0 && z >= 0.0) {
        return +1;
    }
    return 0;
}

int indicator_fires(const ssx_indicator *ind, double z)
{
    int crossing = indicator_crossing(ind, z);
    return crossing != 0 && (ind->direction == 0 || ind->direction == crossing);
}

void indicator_follow(ssx_indicator *ind, double z)
{
    if (ind->sign == 0) {
        ind->sign = z > 0.0 ? 1 : z < 0.0 ? -1 : 0;
        ind->on_zero = 0;
    } else if (ind->on_zero) {
        if (z != 0.0) {
            ind->sign = z > 0.0 ? 1 : -1;
            ind->on_zero = 0;
        }
    } else if (indicator_crossing(ind, z) != 0) {
        ind->sign = -ind->sign;
        ind->on_zero = z == 0.0;
    }
}
