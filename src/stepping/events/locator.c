/* Localization methods: bisection, Illinois, and the default, Illinois helped by secant steps
 * (or, where the indicator's time derivative is known, by cubic Hermite and Newton steps) and
 * held within two trials of bisection. */
#include "locator.h"

#include <math.h>

/* How far past a one-sided secant estimate the next trial aims, as a fraction of its step. */
#define OVERSHOOT 0.1

/* How far short of the cubic Hermite's zero the first trial aims, as a fraction of the bracket:
 * well beyond the cubic's error on smooth indicators (at most 1.9e-7 s, 4e-6 of the 0.05 s
 * step, over the seed pendulum's 129 wall hits in 120 s), and short enough that the Newton step
 * on from there is good to tol_time. */
#define HERMITE_MARGIN 1e-4

/* Regula falsi on the Illinois-weighted end values of one indicator; NAN when not usable. A far
 * end exactly on zero tells nothing of where the indicator reached zero (it may rest there). */
static double illinois_point(const indicator_bracket *end, const bracket_state *st)
{
    if (end->z_right == 0.0 || end->w_left * end->w_right > 0.0 || end->w_left == end->w_right) {
        return NAN;
    }
    return st->a + (st->b - st->a) * end->w_left / (end->w_left - end->w_right);
}

/* The secant through the end the last trial moved, before and after: where the indicator
 * extrapolates to zero. Inside the bracket it lands close to the zero, on the far side of it
 * when the indicator curves away, so that the stale end moves too. NAN when not usable, also
 * when the indicator did not change (a piecewise-constant indicator has no slope there). */
static double secant_point(const indicator_bracket *end, const bracket_state *st)
{
    if (st->moved == SIDE_NONE) {
        return NAN;
    }
    double x = st->moved == SIDE_RIGHT ? st->b : st->a;
    double z = st->moved == SIDE_RIGHT ? end->z_right : end->z_left;
    if (z == end->z_replaced) {
        return NAN;
    }
    double t = x - z * (x - st->replaced) / (z - end->z_replaced);
    return t > st->a && t < st->b ? t : NAN;
}

/* The cubic through the bracket ends' values and slopes, at s in [0, 1] of the bracket. */
static double hermite(const indicator_bracket *end, double h, double s)
{
    double r = 1.0 - s;
    return r * r * ((1.0 + 2.0 * s) * end->z_left + s * h * end->d_left) +
           s * s * ((3.0 - 2.0 * s) * end->z_right - r * h * end->d_right);
}

/* The earliest zero of that cubic inside the bracket: the first sign change among a few
 * pieces, then halvings down to rounding. NAN when it does not change sign. */
static double hermite_point(const indicator_bracket *end, const bracket_state *st)
{
    enum { PIECES = 8, HALVINGS = 60 };
    double h = st->b - st->a;
    double near = hermite(end, h, 0.0);
    double lo = 0.0;
    double hi = NAN;
    for (int k = 1; k <= PIECES && isnan(hi); ++k) {
        double s = (double)k / PIECES;
        if (hermite(end, h, s) * near <= 0.0) {
            hi = s;
        } else {
            lo = s;
        }
    }
    if (isnan(hi)) {
        return NAN;
    }
    for (int k = 0; k < HALVINGS && st->a + h * lo < st->a + h * hi; ++k) {
        double mid = 0.5 * (lo + hi);
        if (hermite(end, h, mid) * near <= 0.0) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    return st->a + h * hi;
}

/* Where the slope puts the zero: before any trial the cubic Hermite through both ends, then a
 * Newton step from the end just moved.
 * The cubic's zero is good to a small fraction of the bracket, not to tol_time: the first trial
 * aims short of it, by HERMITE_MARGIN of the bracket, so that it lands on the near side, where
 * the state it reached is kept and the next trial is a short step on from it (hybrid.c).
 * A Newton step aims a little past the zero, by a sixteenth of tol_value (at most a quarter of
 * tol_time), so that a trial that hits the zero lands on its far side within tol_value and
 * ends the localization. Without tol_value only the bracket's width ends it: a trial after one
 * that moved the far end then aims as far before the zero, so that the near end comes in too.
 * NAN without the slopes it needs. */
static double slope_point(const indicator_bracket *end, const bracket_state *st)
{
    if (end->z_right == 0.0) {
        return NAN; /* it may rest on zero there: no slope tells where it arrived */
    }
    double zero;
    double slope;
    if (st->moved == SIDE_NONE) {
        if (!isfinite(end->d_left) || !isfinite(end->d_right)) {
            return NAN;
        }
        zero = hermite_point(end, st);
        slope = end->d_right;
    } else {
        int right = st->moved == SIDE_RIGHT;
        double x = right ? st->b : st->a;
        double z = right ? end->z_right : end->z_left;
        slope = right ? end->d_right : end->d_left;
        if (!isfinite(slope) || slope == 0.0) {
            return NAN;
        }
        zero = x - z / slope;
    }
    if (!isfinite(zero)) {
        return NAN;
    }
    if (st->moved == SIDE_NONE) {
        /* a zero within the margin of the near end is left to the values: there the cubic's
         * zero may be the near end's own residue (an indicator handled on its far side) */
        double t = zero - fmax(HERMITE_MARGIN * (st->b - st->a), st->tol_time);
        return t > st->a && t < st->b ? t : NAN;
    }
    double past = 0.25 * st->tol_time;
    if (st->tol_value > 0.0) {
        past = fmin(past, st->tol_value / (16.0 * fabs(slope))); /* a zero slope: no bound */
    } else if (st->moved == SIDE_RIGHT) {
        past = -past;
    }
    double t = zero + past;
    return t > st->a && t < st->b ? t : NAN;
}

/* The earliest of an estimate over the crossing indicators; NAN when none is usable. */
static double earliest_point(const indicator_bracket *ends, int n, const bracket_state *st,
                             double (*point)(const indicator_bracket *, const bracket_state *),
                             int skip_flat)
{
    double earliest = NAN;
    for (int i = 0; i < n; ++i) {
        const indicator_bracket *end = &ends[i];
        if (!end->crossing) {
            continue;
        }
        if (skip_flat && st->moved != SIDE_NONE &&
            (st->moved == SIDE_RIGHT ? end->z_right : end->z_left) == end->z_replaced) {
            continue;
        }
        double estimate = point(end, st);
        if (isfinite(estimate) && (isnan(earliest) || estimate < earliest)) {
            earliest = estimate;
        }
    }
    return earliest;
}

static double illinois_estimate(const indicator_bracket *ends, int n, const bracket_state *st)
{
    return earliest_point(ends, n, st, illinois_point, 0);
}

/* Secant steps where they land inside the bracket, Illinois elsewhere; an indicator that kept
 * its value over the last trial is flat there and gives no estimate. */
static double values_estimate(const indicator_bracket *ends, int n, const bracket_state *st)
{
    double t = earliest_point(ends, n, st, secant_point, 1);
    if (isnan(t)) {
        return earliest_point(ends, n, st, illinois_point, 1);
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

/* Slope steps when every crossing indicator has one; otherwise the earliest of them and of
 * the values' estimate. */
static double secant_illinois_estimate(const indicator_bracket *ends, int n,
                                       const bracket_state *st)
{
    double sloped = NAN;
    int all_sloped = 1;
    for (int i = 0; i < n; ++i) {
        if (!ends[i].crossing) {
            continue;
        }
        double t = slope_point(&ends[i], st);
        if (isnan(t)) {
            all_sloped = 0;
        } else if (isnan(sloped) || t < sloped) {
            sloped = t;
        }
    }
    if (all_sloped && !isnan(sloped)) {
        return sloped;
    }
    double valued = values_estimate(ends, n, st);
    return isnan(sloped) ? valued : isnan(valued) ? sloped : fmin(sloped, valued);
}

/* The Illinois modification: an end that stays twice in a row has its weight halved, so the
 * secant cannot creep towards the root from one side only. */
static void illinois_after_trial(indicator_bracket *ends, int n, const bracket_state *st)
{
    if (st->moved != st->moved_before) {
        return;
    }
    for (int i = 0; i < n; ++i) {
        if (st->moved == SIDE_RIGHT) {
            ends[i].w_left *= 0.5;
        } else {
            ends[i].w_right *= 0.5;
        }
    }
}

static double midpoint_estimate(const indicator_bracket *ends, int n, const bracket_state *st)
{
    (void)ends;
    (void)n;
    return 0.5 * (st->a + st->b);
}

static void keep_no_weights(indicator_bracket *ends, int n, const bracket_state *st)
{
    (void)ends;
    (void)n;
    (void)st;
}

/* The default keeps Illinois's superlinear steps on smooth indicators, helped by secant steps
 * through the end just moved, and is held within two trials of bisection: on a
 * piecewise-constant indicator (an FMU output that changes only at the FMU's own steps) plain
 * Illinois can shrink the bracket by a sliver per trial. */
static const locator_method LOCATORS[] = {
    [SSX_ILLINOIS] = {secant_illinois_estimate, illinois_after_trial, 2},
    [SSX_BISECTION] = {midpoint_estimate, keep_no_weights, 0},
    [SSX_ILLINOIS_UNGUARDED] = {illinois_estimate, illinois_after_trial, LOCATOR_UNBOUNDED},
};

const char *const locator_names[] = {
    [SSX_ILLINOIS] = "illinois",
    [SSX_BISECTION] = "bisection",
    [SSX_ILLINOIS_UNGUARDED] = "illinois_unguarded",
    NULL,
};
_Static_assert(sizeof locator_names / sizeof *locator_names ==
                   sizeof LOCATORS / sizeof *LOCATORS + 1,
               "every localization method has a name");

int locator_known(int locator)
{
    return locator >= 0 && locator < (int)(sizeof LOCATORS / sizeof *LOCATORS);
}

const locator_method *locator_method_of(ssx_locator locator)
{
    return &LOCATORS[locator];
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

int locator_budget(const locator_method *method, double w, double tol)
{
    return method->slack == LOCATOR_UNBOUNDED ? LOCATOR_UNBOUNDED
                                              : bisection_count(w, tol) + method->slack;
}

double locator_next_trial(const locator_method *method, const indicator_bracket *ends, int n,
                          const bracket_state *st, double final_width, int budget, int done)
{
    double tol = st->tol_time;
    double a = st->a;
    double b = st->b;
    double t = method->estimate(ends, n, st);
    if (!(t > a && t < b)) {
        t = 0.5 * (a + b);
    }
    /* half a tolerance inside the bracket: the far end also moves when the estimate
     * converges from one side */
    double lo = a + 0.5 * tol;
    double hi = b - 0.5 * tol;
    if (budget != LOCATOR_UNBOUNDED) {
        double reach = ldexp(final_width, budget - done - 1);
        lo = fmax(lo, b - reach);
        hi = fmin(hi, a + reach);
    }
    /* rounding can leave no room at the last halvings: the midpoint then */
    return lo <= hi ? fmin(fmax(t, lo), hi) : 0.5 * (a + b);
}
