/* The hybrid macro step: one snapshot and one coupled step when nothing crosses; otherwise
 * localization of the earliest crossing by restoring and re-stepping the whole system, event
 * handling in superdense time at the far side of the final bracket, and the sign bookkeeping that
 * keeps a handled crossing from firing again. */
#include "hybrid.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "coupling.h"
#include "error.h"
#include "indicator.h"

enum { MACRO_SLOT = 0, PROBE_SLOT = 1 };
/* Fraction of the macro step over which the probe follows a handled state. */
#define PROBE_HORIZON 0.1
/* Event intervals that shrink at least this much each are on their way to an accumulation
 * point (a bouncing ball's shrink by its restitution). */
#define GEOMETRIC_APPROACH 0.9
enum { SIDE_NONE = 0, SIDE_LEFT = 1, SIDE_RIGHT = 2 };
/* How far past a one-sided secant estimate the next trial aims, as a fraction of its step. */
#define OVERSHOOT 0.1

typedef struct {
    double a0;            /* start of the macro piece: the snapshot time */
    double t_end;         /* end of the macro piece */
    double grid_step;     /* the communication step the piece belongs to */
    double a, b;          /* final bracket */
    int iterations;
    int localized;        /* the crossing was bracketed: its trials are in the localization log */
    long do_steps_before; /* statistics at the start of the piece, for the event's cost */
    long restores_before;
} event_bracket;

/* Per-instant workspace, one entry per indicator. */
typedef struct {
    double *band;
    double *z_after;
    double *z_probe;
    int *fired;
    int *next;
    int *listened;
    int *turned_back; /* the first probe moved a fired indicator towards its near side */
} instant_work;

static int snapshot_all(ssx_system *sys, int slot)
{
    for (int i = 0; i < sys->n_components; ++i) {
        if (component_snapshot(sys, sys->components[i], slot) != 0) {
            return -1;
        }
    }
    return 0;
}

static int restore_all(ssx_system *sys, int slot, double t)
{
    for (int i = 0; i < sys->n_components; ++i) {
        if (component_restore(sys, sys->components[i], slot, t) != 0) {
            return -1;
        }
    }
    return record_state_restored(sys, t);
}

/* The whole system from the macro snapshot at a0 to time t: one restore, one coupled step. */
static int step_from_snapshot(ssx_system *sys, double a0, double t)
{
    if (restore_all(sys, MACRO_SLOT, a0) != 0 || coupling_step(sys, a0, t - a0) != 0) {
        return -1;
    }
    return indicators_evaluate(sys, t);
}

static int any_fires(const ssx_system *sys)
{
    for (int i = 0; i < sys->n_indicators; ++i) {
        if (indicator_fires(&sys->indicators[i], sys->indicators[i].value)) {
            return 1;
        }
    }
    return 0;
}

/* The bracket during localization, as the methods see it. */
typedef struct {
    double a, b;
    double replaced;  /* where the end that the last trial replaced was; NAN before any trial */
    int moved;        /* which end the last trial replaced (SIDE_*) */
    int moved_before; /* which end the trial before replaced */
} bracket_state;

/* Regula falsi on the Illinois-weighted end values of one indicator; NAN when not usable. A far
 * end exactly on zero tells nothing of where the indicator reached zero (it may rest there). */
static double illinois_point(const ssx_indicator *ind, const bracket_state *st)
{
    if (ind->z_right == 0.0 || ind->w_left * ind->w_right > 0.0 || ind->w_left == ind->w_right) {
        return NAN;
    }
    return st->a + (st->b - st->a) * ind->w_left / (ind->w_left - ind->w_right);
}

/* The secant through the end the last trial moved, before and after: where the indicator
 * extrapolates to zero. Inside the bracket it lands close to the zero, on the far side of it
 * when the indicator curves away, so that the stale end moves too. NAN when not usable, also
 * when the indicator did not change (a piecewise-constant indicator has no slope there). */
static double secant_point(const ssx_indicator *ind, const bracket_state *st)
{
    if (st->moved == SIDE_NONE) {
        return NAN;
    }
    double x = st->moved == SIDE_RIGHT ? st->b : st->a;
    double z = st->moved == SIDE_RIGHT ? ind->z_right : ind->z_left;
    if (z == ind->z_replaced) {
        return NAN;
    }
    double t = x - z * (x - st->replaced) / (z - ind->z_replaced);
    return t > st->a && t < st->b ? t : NAN;
}

/* The earliest of an estimate over the crossing indicators; NAN when none is usable. */
static double earliest_point(const ssx_system *sys, const bracket_state *st,
                             double (*point)(const ssx_indicator *, const bracket_state *),
                             int skip_flat)
{
    double earliest = NAN;
    for (int i = 0; i < sys->n_indicators; ++i) {
        const ssx_indicator *ind = &sys->indicators[i];
        if (!ind->crossing) {
            continue;
        }
        if (skip_flat && st->moved != SIDE_NONE &&
            (st->moved == SIDE_RIGHT ? ind->z_right : ind->z_left) == ind->z_replaced) {
            continue;
        }
        double estimate = point(ind, st);
        if (isfinite(estimate) && (isnan(earliest) || estimate < earliest)) {
            earliest = estimate;
        }
    }
    return earliest;
}

static double illinois_estimate(const ssx_system *sys, const bracket_state *st)
{
    return earliest_point(sys, st, illinois_point, 0);
}

/* Secant steps where they land inside the bracket, Illinois elsewhere; an indicator that kept
 * its value over the last trial is flat there and gives no estimate. */
static double secant_illinois_estimate(const ssx_system *sys, const bracket_state *st)
{
    double t = earliest_point(sys, st, secant_point, 1);
    if (isnan(t)) {
        return earliest_point(sys, st, illinois_point, 1);
    }
    if (st->moved == st->moved_before) {
        /* one end converges, the other stays: aim a little past the estimate, by a tenth of
         * the step the secant takes, so that the stale end moves in next */
        double x = st->moved == SIDE_RIGHT ? st->b : st->a;
        double past = t + OVERSHOOT * (t - x);
        return past > st->a && past < st->b ? past : t;
    }
    return t;
}

/* The Illinois modification: an end that stays twice in a row has its weight halved, so the
 * secant cannot creep towards the root from one side only. */
static void illinois_after_trial(ssx_system *sys, const bracket_state *st)
{
    if (st->moved != st->moved_before) {
        return;
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        ssx_indicator *ind = &sys->indicators[i];
        if (st->moved == SIDE_RIGHT) {
            ind->w_left *= 0.5;
        } else {
            ind->w_right *= 0.5;
        }
    }
}

static double midpoint_estimate(const ssx_system *sys, const bracket_state *st)
{
    (void)sys;
    return 0.5 * (st->a + st->b);
}

static void keep_no_weights(ssx_system *sys, const bracket_state *st)
{
    (void)sys;
    (void)st;
}

enum { UNBOUNDED = -1 };

/* A localization method: where to try next in the bracket, and what to update once a trial has
 * moved one end. slack bounds its iterations to bisection's count plus slack. */
typedef struct {
    double (*estimate)(const ssx_system *sys, const bracket_state *st);
    void (*after_trial)(ssx_system *sys, const bracket_state *st);
    int slack;
} locator_method;

/* The default keeps Illinois's superlinear steps on smooth indicators, helped by secant steps
 * through the end just moved, and is held within two trials of bisection: on a
 * piecewise-constant indicator (an FMU output that changes only at the FMU's own steps) plain
 * Illinois can shrink the bracket by a sliver per trial. */
static const locator_method LOCATORS[] = {
    [SSX_ILLINOIS] = {secant_illinois_estimate, illinois_after_trial, 2},
    [SSX_BISECTION] = {midpoint_estimate, keep_no_weights, 0},
    [SSX_ILLINOIS_UNGUARDED] = {illinois_estimate, illinois_after_trial, UNBOUNDED},
};

int hybrid_locator_known(int locator)
{
    return locator >= 0 && locator < (int)(sizeof LOCATORS / sizeof *LOCATORS);
}

/* Bisection's iteration count from a bracket of width w down to tol. */
static int bisection_count(double w, double tol)
{
    int n = 0;
    for (; w > tol; w *= 0.5) {
        ++n;
    }
    return n;
}

/* The next trial time in [a, b]. A budgeted method's estimate is kept where, whichever end the
 * trial replaces, the bracket left over still comes down to final_width by halving within the
 * remaining budget: budget - done - 1 halvings after this trial. */
static double next_trial(const ssx_system *sys, const locator_method *method,
                         const bracket_state *st, double final_width, int budget, int done)
{
    double tol = sys->hybrid.tol_time;
    double a = st->a;
    double b = st->b;
    double t = method->estimate(sys, st);
    if (!(t > a && t < b)) {
        t = 0.5 * (a + b);
    }
    /* half a tolerance inside the bracket: the far end also moves when the estimate
     * converges from one side */
    double lo = a + 0.5 * tol;
    double hi = b - 0.5 * tol;
    if (budget != UNBOUNDED) {
        double reach = ldexp(final_width, budget - done - 1);
        lo = fmax(lo, b - reach);
        hi = fmin(hi, a + reach);
    }
    /* rounding can leave no room at the last halvings: the midpoint then */
    return lo <= hi ? fmin(fmax(t, lo), hi) : 0.5 * (a + b);
}

/* Every indicator crossing at the far end is within tol_value of zero. An exact zero does not
 * count: the indicator may have reached it long before and rested there. */
static int far_side_converged(const ssx_system *sys)
{
    if (!(sys->hybrid.tol_value > 0.0)) {
        return 0;
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        const ssx_indicator *ind = &sys->indicators[i];
        if (ind->crossing && !(ind->z_right != 0.0 && fabs(ind->z_right) <= sys->hybrid.tol_value)) {
            return 0;
        }
    }
    return 1;
}

/* A row of the localization log with every indicator's current value (left: the values
 * at the bracket's left end instead). */
static int log_row(ssx_system *sys, double t, double a, double b, int left)
{
    double *values = localization_log_row(&sys->localization, t, a, b);
    if (values == NULL) {
        return fail(sys, -1, -1, t, "out of memory logging the localization at t=%.17g", t);
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        values[i] = left ? sys->indicators[i].z_left : sys->indicators[i].value;
    }
    return 0;
}

/* Shrinks [a0, t_end] around the earliest crossing; leaves the system in the state at b. */
static int locate(ssx_system *sys, event_bracket *br)
{
    const ssx_hybrid_options *opt = &sys->hybrid;
    const locator_method *method = &LOCATORS[opt->locator];
    double a = br->a0;
    double b = br->t_end;
    for (int i = 0; i < sys->n_indicators; ++i) {
        ssx_indicator *ind = &sys->indicators[i];
        ind->z_right = ind->value;
        ind->w_left = ind->z_left;
        ind->w_right = ind->z_right;
        ind->crossing = indicator_fires(ind, ind->value);
    }
    localization_log_begin(&sys->localization, sys->n_indicators);
    br->localized = 1;
    if (log_row(sys, a, a, b, 1) != 0 || log_row(sys, b, a, b, 0) != 0) {
        return -1;
    }
    int halvings = bisection_count(b - a, opt->tol_time);
    /* a few roundings of the times inside tol_time: the last trials of a budgeted method land
     * on its window's edges, which must not leave the bracket a hair above tol_time */
    double final_width = opt->tol_time - 16.0 * DBL_EPSILON * fmax(fabs(a), fabs(b));
    int budget = method->slack == UNBOUNDED ? UNBOUNDED : halvings + method->slack;
    bracket_state st = {.a = a, .b = b, .replaced = NAN, .moved = SIDE_NONE,
                        .moved_before = SIDE_NONE};
    br->iterations = 0;
    while (st.b - st.a > opt->tol_time && !far_side_converged(sys)) {
        if (br->iterations >= opt->max_iterations) {
            return fail(sys, -1, -1, st.a,
                        "event localization did not reach tol_time=%g within %d iterations: "
                        "bracket [%.17g, %.17g]",
                        opt->tol_time, opt->max_iterations, st.a, st.b);
        }
        double t = next_trial(sys, method, &st, final_width, budget, br->iterations);
        br->iterations++;
        sys->stats.localization_iterations++;
        if (step_from_snapshot(sys, br->a0, t) != 0) {
            return -1;
        }
        if (opt->record_internal_steps && record_sample(sys, t, -1) != 0) {
            return -1;
        }
        int side = any_fires(sys) ? SIDE_RIGHT : SIDE_LEFT;
        for (int i = 0; i < sys->n_indicators; ++i) {
            ssx_indicator *ind = &sys->indicators[i];
            if (side == SIDE_RIGHT) {
                ind->z_replaced = ind->z_right;
                ind->z_right = ind->w_right = ind->value;
                ind->crossing = indicator_fires(ind, ind->value);
            } else {
                ind->z_replaced = ind->z_left;
                ind->z_left = ind->w_left = ind->value;
            }
        }
        st.replaced = side == SIDE_RIGHT ? st.b : st.a;
        st.moved_before = st.moved;
        st.moved = side;
        if (side == SIDE_RIGHT) {
            st.b = t;
        } else {
            st.a = t;
        }
        method->after_trial(sys, &st);
        if (log_row(sys, t, st.a, st.b, 0) != 0) {
            return -1;
        }
    }
    a = st.a;
    b = st.b;
    int state_at_b = st.moved != SIDE_LEFT;
    if (!state_at_b && step_from_snapshot(sys, br->a0, b) != 0) {
        return -1;
    }
    br->a = a;
    br->b = b;
    return 0;
}

static void work_free(instant_work *w)
{
    free(w->band);
    free(w->fired);
}

static int work_init(instant_work *w, ssx_system *sys, double t)
{
    memset(w, 0, sizeof *w);
    size_t n = (size_t)sys->n_indicators;
    w->band = malloc(3 * n * sizeof(double));
    w->fired = malloc(4 * n * sizeof(int));
    if (w->band == NULL || w->fired == NULL) {
        work_free(w);
        return fail(sys, -1, -1, t, "out of memory handling an event");
    }
    w->z_after = w->band + n;
    w->z_probe = w->z_after + n;
    w->next = w->fired + n;
    w->listened = w->next + n;
    w->turned_back = w->listened + n;
    return 0;
}

/* |z| below which a fired indicator counts as sitting on its zero: the localization residue. */
static double residue_band(const ssx_system *sys, const event_bracket *br,
                           const ssx_indicator *ind, double z)
{
    double slope = fabs(ind->z_right - ind->z_left) / fmax(br->b - br->a, 1e-300);
    return 2.0 * fmax(sys->hybrid.tol_value, fmax(fabs(z), slope * sys->hybrid.tol_time));
}

static int sign_of(double z, int otherwise)
{
    return z > 0.0 ? 1 : z < 0.0 ? -1 : otherwise;
}

static int near_zero(const instant_work *w, int i)
{
    return w->fired[i] && fabs(w->z_after[i]) <= w->band[i];
}

/* Where the fired indicators that still sit on their zero are going: steps from b, ten times
 * longer each, until every one of them has left its residue band (or the step reaches
 * delta_max); the state goes back to b after each. */
static int probe(ssx_system *sys, double b, double delta_max, instant_work *w)
{
    if (snapshot_all(sys, PROBE_SLOT) != 0) {
        return -1;
    }
    double delta = 10.0 * sys->hybrid.tol_time;
    for (int first = 1;; first = 0) {
        if (coupling_step(sys, b, delta) != 0 || indicators_evaluate(sys, b + delta) != 0) {
            return -1;
        }
        int settled = 1;
        for (int i = 0; i < sys->n_indicators; ++i) {
            const ssx_indicator *ind = &sys->indicators[i];
            w->z_probe[i] = ind->value;
            if (first) {
                /* ind->sign is the far side here */
                w->turned_back[i] = (ind->value - w->z_after[i]) * (double)ind->sign < 0.0;
            }
            settled &= !near_zero(w, i) || fabs(ind->value) > w->band[i];
        }
        if (restore_all(sys, PROBE_SLOT, b) != 0) {
            return -1;
        }
        if (settled || delta >= delta_max) {
            break;
        }
        delta = fmin(10.0 * delta, delta_max);
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        sys->indicators[i].value = w->z_after[i];
    }
    return 0;
}

static int notify_listeners(ssx_system *sys, double b, instant_work *w)
{
    for (int c = 0; c < sys->n_components; ++c) {
        int n = 0;
        for (int i = 0; i < sys->n_indicators; ++i) {
            if (!w->fired[i]) {
                continue;
            }
            for (int k = 0; k < sys->n_event_links; ++k) {
                if (sys->event_links[k].indicator == i && sys->event_links[k].listener == c) {
                    w->listened[n++] = i;
                    break;
                }
            }
        }
        if (n > 0 && component_handle_events(sys, sys->components[c], w->listened, n, b) != 0) {
            return -1;
        }
    }
    return 0;
}

/* Two firings of one indicator this close are chattering. With zeno_min_interval set, that is
 * the whole rule. By default the scale is a tenth of the communication step (the horizon over
 * which the probe judges where a handled state goes): crossings that come back faster are finer
 * than the grid resolves, since between two grid points a master sees only the signs at the
 * ends. They are still followed while their intervals shrink geometrically, the way to an
 * accumulation point, which ten times tol_time or the residue test of settle_signs then stops
 * precisely; once they stop shrinking the model chatters at a fixed fine scale (an explicit
 * Euler FMU gains speed at every bounce and settles into flights of a few of its own steps,
 * bouncing for ever). */
static int chattering(const ssx_system *sys, const event_bracket *br, const ssx_indicator *ind,
                      double interval)
{
    if (sys->hybrid.zeno_min_interval > 0.0) {
        return interval < sys->hybrid.zeno_min_interval;
    }
    if (interval < 10.0 * sys->hybrid.tol_time) {
        return 1;
    }
    return interval < PROBE_HORIZON * br->grid_step &&
           !(interval <= GEOMETRIC_APPROACH * ind->last_interval);
}

static int check_zeno(ssx_system *sys, const event_bracket *br, int micro, const instant_work *w)
{
    double b = br->b;
    for (int i = 0; i < sys->n_indicators; ++i) {
        ssx_indicator *ind = &sys->indicators[i];
        /* cascades at one instant are bounded by max_microsteps instead */
        if (!w->fired[i] || micro != 0 || !ind->fired_before) {
            continue;
        }
        double interval = b - ind->last_event_time;
        if (!chattering(sys, br, ind, interval)) {
            continue;
        }
        const char *name = sys->components[ind->component]->name;
        if (sys->hybrid.zeno_min_interval > 0.0 || interval < 10.0 * sys->hybrid.tol_time) {
            return fail_zeno(sys, ind->component, i, b,
                             "indicator %d of component '%s' fired again at t=%.17g, only %.3g "
                             "after its previous event (event number %ld): chattering (Zeno) "
                             "behaviour; the minimum interval is %.3g",
                             i, name, b, interval, ind->fire_count + 1,
                             fmax(sys->hybrid.zeno_min_interval, 10.0 * sys->hybrid.tol_time));
        }
        return fail_zeno(sys, ind->component, i, b,
                         "indicator %d of component '%s' fired again at t=%.17g, only %.3g after "
                         "its previous event (event number %ld), within a tenth of the "
                         "communication step, and its intervals no longer shrink (the previous "
                         "one was %.3g): chattering (Zeno) behaviour; a smaller step or "
                         "zeno_min_interval follows such events",
                         i, name, b, interval, ind->fire_count + 1, ind->last_interval);
    }
    return 0;
}

/* Signs after a handling round; marks the cascading crossings in w->next. */
static int settle_signs(ssx_system *sys, double b, const event_bracket *br, instant_work *w)
{
    int need_probe = 0;
    for (int i = 0; i < sys->n_indicators; ++i) {
        w->z_after[i] = sys->indicators[i].value;
        w->turned_back[i] = 0;
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        need_probe |= near_zero(w, i);
    }
    /* the probe stays well inside the macro step it belongs to */
    double delta_max = fmax(10.0 * sys->hybrid.tol_time, PROBE_HORIZON * (br->t_end - br->a0));
    if (need_probe && probe(sys, b, delta_max, w) != 0) {
        return -1;
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        ssx_indicator *ind = &sys->indicators[i];
        /* a fired indicator still within its residue band goes where the probe says; any other
         * sign change was made by the handling itself */
        int from_probe = near_zero(w, i);
        double z = from_probe ? w->z_probe[i] : w->z_after[i];
        int new_sign = sign_of(z, ind->sign);
        /* Turned back towards its near side yet unable to leave the far one: the handled state
         * cannot climb out of the residue at b (a ball too slow to leave the floor) and would
         * sink unseen. That is the end of a Zeno sequence. */
        if (from_probe && new_sign == ind->sign && w->turned_back[i]) {
            return fail_zeno(sys, ind->component, i, b,
                             "indicator %d of component '%s' cannot leave zero after its event "
                             "at t=%.17g (event number %ld): the handled state turns back but "
                             "stays within the residue %.3g; chattering (Zeno) behaviour",
                             i, sys->components[ind->component]->name, b, ind->fire_count,
                             fabs(w->z_after[i]));
        }
        /* a handler that moves a fired indicator back across is a new crossing; one that
         * moves an indicator resting on zero from an earlier instant only ends the rest */
        int resting = ind->on_zero && !w->fired[i];
        w->next[i] = 0;
        if (ind->sign != 0 && new_sign != ind->sign && !from_probe && !resting) {
            int crossing = new_sign > 0 ? 1 : -1;
            w->next[i] = ind->direction == 0 || ind->direction == crossing;
        }
        ind->sign = new_sign;
        ind->on_zero = ind->on_zero && z == 0.0;
    }
    return 0;
}

static int add_event_records(ssx_system *sys, double b, int micro, const event_bracket *br,
                             const instant_work *w)
{
    int first = 1;
    for (int i = 0; i < sys->n_indicators; ++i) {
        if (!w->fired[i]) {
            continue;
        }
        /* the instant's cost goes on its first record, so sums over records stay right */
        int carries_cost = first && micro == 0;
        ssx_event_record record = {
            .t = b,
            .micro = micro,
            .indicator = i,
            .component = sys->indicators[i].component,
            .iterations = carries_cost ? br->iterations : 0,
            .rollbacks = carries_cost ? (int)(sys->stats.state_restores - br->restores_before) : 0,
            .do_steps = carries_cost ? sys->stats.do_step_calls - br->do_steps_before : 0,
        };
        first = 0;
        if (micro == 0 && br->localized) {
            if (localization_log_publish(&sys->localization, &record) != 0) {
                return fail(sys, record.component, i, b, "out of memory recording an event");
            }
        } else {
            localization_log_none(&sys->localization, &record);
        }
        if (record_event(sys, &record) != 0) {
            return -1;
        }
    }
    return 0;
}

/* Handles the instant b: rounds of (record before, notify, settle, record after) while
 * handling makes indicators cross, up to max_microsteps rounds. */
static int handle_instant(ssx_system *sys, const event_bracket *br, instant_work *w,
                          int record_before)
{
    double b = br->b;
    if (record_before && record_sample(sys, b, 0) != 0) {
        return -1;
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        ssx_indicator *ind = &sys->indicators[i];
        w->fired[i] = indicator_fires(ind, ind->value);
        indicator_follow(ind, ind->value);
        w->band[i] = residue_band(sys, br, ind, ind->value);
    }
    for (int micro = 0;; ++micro) {
        if (micro >= sys->hybrid.max_microsteps) {
            int first = -1;
            for (int i = 0; i < sys->n_indicators && first < 0; ++i) {
                first = w->fired[i] ? i : -1;
            }
            return fail_zeno(sys, first >= 0 ? sys->indicators[first].component : -1, first, b,
                             "more than %d micro steps of cascading events at t=%.17g (the "
                             "handlers keep making indicators cross; first: indicator %d)",
                             sys->hybrid.max_microsteps, b, first);
        }
        if (check_zeno(sys, br, micro, w) != 0) {
            return -1;
        }
        for (int i = 0; i < sys->n_indicators; ++i) {
            ssx_indicator *ind = &sys->indicators[i];
            if (!w->fired[i]) {
                continue;
            }
            if (micro == 0) {
                ind->last_interval = ind->fired_before ? b - ind->last_event_time : INFINITY;
            }
            ind->fired_before = 1;
            ind->last_event_time = b;
            ind->fire_count++;
        }
        sys->stats.events++;
        if (notify_listeners(sys, b, w) != 0 || coupling_settle(sys, b) != 0 ||
            record_sample(sys, b, micro + 1) != 0 || indicators_evaluate(sys, b) != 0 ||
            settle_signs(sys, b, br, w) != 0 || add_event_records(sys, b, micro, br, w) != 0) {
            return -1;
        }
        int cascades = 0;
        for (int i = 0; i < sys->n_indicators; ++i) {
            if (w->next[i]) {
                cascades = 1;
                /* handling put it there, no localization residue: only tol_value is zero */
                w->band[i] = 2.0 * sys->hybrid.tol_value;
            }
            w->fired[i] = w->next[i];
        }
        if (!cascades) {
            return 0;
        }
    }
}

/* An indicator starting exactly on zero has no side yet: the probe tells where it goes. Going to
 * the far side of its direction is a crossing at the start itself, handled there (its sample
 * before handling is already recorded). Done once per initialization: an indicator that stays
 * on zero later takes its side from its first nonzero value, without an event. */
static int resolve_zero_start(ssx_system *sys, double a0, double t_next)
{
    if (!sys->zero_start_pending) {
        return 0;
    }
    sys->zero_start_pending = 0;
    int unknown = 0;
    for (int i = 0; i < sys->n_indicators; ++i) {
        unknown |= sys->indicators[i].sign == 0;
    }
    if (!unknown) {
        return 0;
    }
    instant_work w;
    if (work_init(&w, sys, a0) != 0) {
        return -1;
    }
    event_bracket br = {.a0 = a0,
                        .t_end = t_next,
                        .grid_step = t_next - a0,
                        .a = a0,
                        .b = a0,
                        .do_steps_before = sys->stats.do_step_calls,
                        .restores_before = sys->stats.state_restores};
    for (int i = 0; i < sys->n_indicators; ++i) {
        ssx_indicator *ind = &sys->indicators[i];
        ind->z_left = ind->z_right = ind->value;
        w.fired[i] = ind->sign == 0;
        w.z_after[i] = ind->value;
        w.band[i] = 0.0;
    }
    int status =
        probe(sys, a0, fmax(10.0 * sys->hybrid.tol_time, PROBE_HORIZON * (t_next - a0)), &w);
    int fires = 0;
    for (int i = 0; status == 0 && i < sys->n_indicators; ++i) {
        ssx_indicator *ind = &sys->indicators[i];
        if (ind->sign != 0 || w.z_probe[i] == 0.0) {
            continue;
        }
        int going = w.z_probe[i] > 0.0 ? 1 : -1;
        int crossing = ind->direction == 0 || ind->direction == going;
        /* a crossing starts on the near side, so that the zero at a0 counts as the far one */
        ind->sign = crossing ? -going : going;
        fires |= crossing;
    }
    if (status == 0 && fires) {
        sys->time = a0;
        status = handle_instant(sys, &br, &w, 0);
    }
    work_free(&w);
    return status;
}

int hybrid_step(ssx_system *sys, double t, double t_next)
{
    double a0 = t;
    while (a0 < t_next) {
        sys->time = a0;
        if (resolve_zero_start(sys, a0, t_next) != 0) {
            return -1;
        }
        event_bracket br = {.a0 = a0,
                            .t_end = t_next,
                            .grid_step = t_next - t,
                            .do_steps_before = sys->stats.do_step_calls,
                            .restores_before = sys->stats.state_restores};
        for (int i = 0; i < sys->n_indicators; ++i) {
            sys->indicators[i].z_left = sys->indicators[i].value;
        }
        if (snapshot_all(sys, MACRO_SLOT) != 0 || coupling_step(sys, a0, t_next - a0) != 0 ||
            indicators_evaluate(sys, t_next) != 0) {
            return -1;
        }
        sys->stats.macro_steps++;
        if (!any_fires(sys)) {
            for (int i = 0; i < sys->n_indicators; ++i) {
                indicator_follow(&sys->indicators[i], sys->indicators[i].value);
            }
            sys->time = t_next;
            return record_grid_point(sys, t_next);
        }
        if (locate(sys, &br) != 0) {
            return -1;
        }
        sys->time = br.b;
        instant_work w;
        if (work_init(&w, sys, br.b) != 0) {
            return -1;
        }
        int status = handle_instant(sys, &br, &w, 1);
        work_free(&w);
        if (status != 0) {
            return -1;
        }
        a0 = br.b;
    }
    return 0;
}
