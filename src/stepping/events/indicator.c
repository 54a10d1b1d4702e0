/* Indicator evaluation and crossing detection. */
#include "indicator.h"

#include <math.h>

#include "component.h"
#include "error.h"
#include "fmu_backend.h"
#include "fmu_binding.h"
#include "system.h"

void indicators_watch_outputs(ssx_system *sys)
{
    for (int i = 0; i < sys->n_indicators; ++i) {
        const ssx_indicator *indicator = &sys->indicators[i];
        if (indicator->output >= 0) {
            sys->components[indicator->component]->output_watch[indicator->output].feeds = 1;
        }
    }
}

int indicators_evaluate(ssx_system *sys, double t)
{
    for (int i = 0; i < sys->n_indicators; ++i) {
        const ssx_indicator *ind = &sys->indicators[i];
        const ssx_component *c = sys->components[ind->component];
        double value;
        if (ind->output >= 0) {
            value = c->outputs[ind->output];
        } else if (ind->evaluate(ind->user, t, &value) != 0) {
            return fail_kind(sys, SSX_ERROR_CALLBACK, ind->component, i, t,
                             "component '%s': the Python function of indicator %d failed at "
                             "t=%.17g",
                             c->name, i, t);
        }
        if (!isfinite(value)) {
            return fail_kind(sys, SSX_ERROR_NON_FINITE, ind->component, i, t,
                             "component '%s': indicator %d is not finite (%g) at t=%.17g", c->name,
                             i, value, t);
        }
        sys->indicator_states[i].value = value;
    }
    return 0;
}

int indicator_slope(ssx_system *sys, int i, double t, double *slope)
{
    const ssx_indicator *ind = &sys->indicators[i];
    *slope = NAN;
    if (!ind->has_slope) {
        return 0;
    }
    const ssx_component *c = sys->components[ind->component];
    ssx_fmu *fmu = c->ops->fmu(c); /* it runs one: ssx_set_indicator_slope checked */
    double value;
    int status = ssx_fmu_get_real(fmu, &ind->slope_vr, 1, &value);
    if (!fmi_ok(status)) {
        return fail_fmi(sys, c, fmu, t, status, ssx_fmu_function_name(fmu, SLOT_GET_REAL));
    }
    /* a slope that is no number only leaves the estimate to the values */
    *slope = isfinite(value) ? value : NAN;
    return 0;
}

void indicators_start(ssx_system *sys)
{
    for (int i = 0; i < sys->n_indicators; ++i) {
        indicator_state *s = &sys->indicator_states[i];
        s->sign = 0;
        s->fired_before = 0;
        s->fire_count = 0;
        indicator_follow(s, s->value);
    }
}

int indicator_crossing(const indicator_state *s, double z)
{
    if (s->on_zero) {
        return 0;
    }
    if (s->sign > 0 && z <= 0.0) {
        return -1;
    }
    if (s->sign < 0 && z >= 0.0) {
        return +1;
    }
    return 0;
}

int indicator_fires(const ssx_indicator *ind, const indicator_state *s, double z)
{
    int crossing = indicator_crossing(s, z);
    return crossing != 0 && (ind->direction == 0 || ind->direction == crossing);
}

void indicator_follow(indicator_state *s, double z)
{
    if (s->sign == 0) {
        s->sign = z > 0.0 ? 1 : z < 0.0 ? -1 : 0;
        s->on_zero = 0;
    } else if (s->on_zero) {
        if (z != 0.0) {
            s->sign = z > 0.0 ? 1 : -1;
            s->on_zero = 0;
        }
    } else if (indicator_crossing(s, z) != 0) {
        s->sign = -s->sign;
        s->on_zero = z == 0.0;
    }
}
