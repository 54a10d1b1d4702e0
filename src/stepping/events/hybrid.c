/* The hybrid macro step: one snapshot and one coupled step when nothing crosses; otherwise
 * localization of the earliest crossing by restoring and re-stepping the whole system (where
 * to try next is the localization method's choice, locator.c), event handling in superdense
 * time at the far side of the final bracket, and the sign bookkeeping that keeps a handled
 * crossing from firing again. */
#include "hybrid.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "component_calls.h"
#include "coupling.h"
#include "error.h"
#include "event_source.h"
#include "indicator.h"
#include "interrupt.h"
#include "locator.h"
#include "own_events.h"
#include "recording.h"
#include "system_state.h"
#include "zeno.h"

/* Slot 1 serves localization (the bracket's near end) and then the probe after the event. */
enum { NEAR_SLOT = 1, PROBE_SLOT = 1 };

/* The hybrid algorithm's own state: made by hybrid_prepare at ssx_initialize, held for it by
 * the system (sys->algorithm_workspace), freed by hybrid_release. */
typedef struct {
    indicator_bracket *brackets; /* the localization workspace, one per indicator */
    int zero_start_pending;      /* indicators starting on zero still need their side probed */
    size_t *own_pending; /* per component, its own events pending at the piece's start */
} hybrid_workspace;

static hybrid_workspace *workspace(const ssx_system *sys)
{
    return sys->algorithm_workspace;
}

/* Fraction of the macro step over which the probe follows a handled state. */
#define PROBE_HORIZON 0.1

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

/* The whole system, in the state it has at time `from`, to time t: one coupled step, the
 * indicators at t. */
static int step_on(ssx_system *sys, double from, double t)
{
    if (coupling_step(sys, from, t - from) != 0) {
        return -1;
    }
    return indicators_evaluate(sys, t);
}

/* The indicators' slopes at the current state (time t) into one end of their brackets (those
 * without a slope get NAN there). */
static int read_slopes(ssx_system *sys, double t, int side)
{
    for (int i = 0; i < sys->n_indicators; ++i) {
        indicator_bracket *end = &workspace(sys)->brackets[i];
        if (indicator_slope(sys, i, t, side == SIDE_RIGHT ? &end->d_right : &end->d_left) != 0) {
            return -1;
        }
    }
    return 0;
}

/* Indicator i crosses in its direction at its current value. */
static int fires_now(const ssx_system *sys, int i)
{
    const indicator_state *s = &sys->indicator_states[i];
    return indicator_fires(&sys->indicators[i], s, s->value);
}

static int any_fires(const ssx_system *sys)
{
    for (int i = 0; i < sys->n_indicators; ++i) {
        if (fires_now(sys, i)) {
            return 1;
        }
    }
    return 0;
}

/* Every indicator crossing at the far end is within tol_value of zero. An exact zero does not
 * count: the indicator may have reached it long before and rested there. */
static int far_side_converged(const ssx_system *sys)
{
    if (!(sys->hybrid.tol_value > 0.0)) {
        return 0;
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        const indicator_bracket *end = &workspace(sys)->brackets[i];
        if (end->crossing && !(end->z_right != 0.0 && fabs(end->z_right) <= sys->hybrid.tol_value)) {
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
        values[i] = left ? workspace(sys)->brackets[i].z_left : sys->indicator_states[i].value;
    }
    return 0;
}

/* Shrinks [a0, t_end] around the earliest crossing; leaves the system in the state at b.
 * Every trial steps from the bracket's near end: on from where the system is when the trial
 * before moved that end (its state is then kept in NEAR_SLOT for later trials), else from that
 * slot, or from the piece's start a0 while no trial has landed on the near side. Only the
 * stretch past the near end is stepped again, and the trajectory is the one through the near
 * end. The far end of a final bracket that the near end moved into last was reached from an
 * earlier near end: stepped again on this trajectory it may not cross there yet (the caller
 * then goes on from b, hybrid_end_piece). */
static int locate(ssx_system *sys, event_bracket *br)
{
    const ssx_hybrid_options *opt = &sys->hybrid;
    const locator_method *method = locator_method_of(opt->locator);
    int n = sys->n_indicators;
    indicator_bracket *ends = workspace(sys)->brackets;
    double a = br->a0;
    double b = br->t_end;
    for (int i = 0; i < n; ++i) {
        ends[i].z_right = sys->indicator_states[i].value;
        ends[i].w_left = ends[i].z_left;
        ends[i].w_right = ends[i].z_right;
        ends[i].crossing = fires_now(sys, i);
    }
    if (read_slopes(sys, b, SIDE_RIGHT) != 0) {
        return -1;
    }
    localization_log_begin(&sys->localization, sys->n_indicators);
    br->localized = 1;
    if (log_row(sys, a, a, b, 1) != 0 || log_row(sys, b, a, b, 0) != 0) {
        return -1;
    }
    /* a few roundings of the times inside tol_time: the last trials of a budgeted method land
     * on its window's edges, which must not leave the bracket a hair above tol_time */
    double final_width = opt->tol_time - 16.0 * DBL_EPSILON * fmax(fabs(a), fabs(b));
    int budget = locator_budget(method, b - a, opt->tol_time);
    bracket_state st = {.a = a, .b = b, .replaced = NAN, .moved = SIDE_NONE,
                        .moved_before = SIDE_NONE, .tol_time = opt->tol_time,
                        .tol_value = opt->tol_value};
    br->iterations = 0;
    int near_saved = 0; /* NEAR_SLOT holds the state at st.a */
    while (st.b - st.a > opt->tol_time && !far_side_converged(sys)) {
        if (run_interrupted(sys, st.a) != 0) {
            return -1;
        }
        if (br->iterations >= opt->max_iterations) {
            return fail(sys, -1, -1, st.a,
                        "event localization did not reach tol_time=%g within %d iterations: "
                        "bracket [%.17g, %.17g]",
                        opt->tol_time, opt->max_iterations, st.a, st.b);
        }
        if (st.moved == SIDE_LEFT) {
            if (system_snapshot(sys, NEAR_SLOT) != 0) {
                return -1;
            }
            near_saved = 1;
        } else if (near_saved) {
            if (system_restore(sys, NEAR_SLOT, st.a) != 0) {
                return -1;
            }
        } else if (system_restore(sys, MACRO_SLOT, br->a0) != 0 ||
                   /* the slopes at a0, read once before the first estimate */
                   (br->iterations == 0 && read_slopes(sys, br->a0, SIDE_LEFT) != 0)) {
            return -1;
        }
        double t = locator_next_trial(method, ends, n, &st, final_width, budget, br->iterations);
        br->iterations++;
        sys->stats.localization_iterations++;
        if (step_on(sys, st.a, t) != 0) {
            return -1;
        }
        if (opt->record_internal_steps && record_sample(sys, t, -1) != 0) {
            return -1;
        }
        int side = any_fires(sys) ? SIDE_RIGHT : SIDE_LEFT;
        if (read_slopes(sys, t, side) != 0) {
            return -1;
        }
        for (int i = 0; i < n; ++i) {
            double z = sys->indicator_states[i].value;
            if (side == SIDE_RIGHT) {
                ends[i].z_replaced = ends[i].z_right;
                ends[i].z_right = ends[i].w_right = z;
                ends[i].crossing = fires_now(sys, i);
            } else {
                ends[i].z_replaced = ends[i].z_left;
                ends[i].z_left = ends[i].w_left = z;
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
        method->after_trial(ends, n, &st);
        if (log_row(sys, t, st.a, st.b, 0) != 0) {
            return -1;
        }
    }
    /* the last trial moved the near end: on from there to the far one */
    if (st.moved == SIDE_LEFT && step_on(sys, st.a, st.b) != 0) {
        return -1;
    }
    br->a = st.a;
    br->b = st.b;
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
                           const indicator_bracket *end, double z)
{
    double slope = fabs(end->z_right - end->z_left) / fmax(br->b - br->a, 1e-300);
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
    if (system_snapshot(sys, PROBE_SLOT) != 0) {
        return -1;
    }
    double delta = distinct_events_interval(&sys->hybrid);
    for (int first = 1;; first = 0) {
        if (coupling_step(sys, b, delta) != 0 || indicators_evaluate(sys, b + delta) != 0) {
            return -1;
        }
        int settled = 1;
        for (int i = 0; i < sys->n_indicators; ++i) {
            const indicator_state *s = &sys->indicator_states[i];
            w->z_probe[i] = s->value;
            if (first) {
                /* s->sign is the far side here */
                w->turned_back[i] = (s->value - w->z_after[i]) * (double)s->sign < 0.0;
            }
            settled &= !near_zero(w, i) || fabs(s->value) > w->band[i];
        }
        if (system_restore(sys, PROBE_SLOT, b) != 0) {
            return -1;
        }
        if (settled || delta >= delta_max) {
            break;
        }
        delta = fmin(10.0 * delta, delta_max);
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        sys->indicator_states[i].value = w->z_after[i];
    }
    return 0;
}

/* Chattering by zeno.h's rule. The master's resolution is a tenth of the communication step
 * (the horizon over which the probe judges where a handled state goes): crossings that come
 * back faster are finer than the grid resolves, since between two grid points a master sees
 * only the signs at the ends. The residue test of settle_signs stops an accumulation point
 * precisely too; once the intervals stop shrinking the model chatters at a fixed fine scale (an
 * explicit Euler FMU gains speed at every bounce and settles into flights of a few of its own
 * steps, bouncing for ever). */
static int check_zeno(ssx_system *sys, const event_bracket *br, int micro, const instant_work *w)
{
    double b = br->b;
    for (int i = 0; i < sys->n_indicators; ++i) {
        const indicator_state *s = &sys->indicator_states[i];
        int component = sys->indicators[i].component;
        /* cascades at one instant are bounded by max_microsteps instead */
        if (!w->fired[i] || micro != 0 || !s->fired_before) {
            continue;
        }
        double interval = b - s->last_event_time;
        zeno_verdict verdict = zeno_judge(&sys->hybrid, interval, s->last_interval,
                                          PROBE_HORIZON * br->grid_step);
        if (verdict == ZENO_NONE) {
            continue;
        }
        const char *name = sys->components[component]->name;
        if (verdict == ZENO_TOO_CLOSE) {
            return fail_zeno(sys, component, i, b,
                             "indicator %d of component '%s' fired again at t=%.17g, only %.3g "
                             "after its previous event (event number %ld): chattering (Zeno) "
                             "behaviour; the minimum interval is %.3g",
                             i, name, b, interval, s->fire_count + 1,
                             zeno_min_interval(&sys->hybrid));
        }
        return fail_zeno(sys, component, i, b,
                         "indicator %d of component '%s' fired again at t=%.17g, only %.3g after "
                         "its previous event (event number %ld), within a tenth of the "
                         "communication step, and its intervals no longer shrink (the previous "
                         "one was %.3g): chattering (Zeno) behaviour; a smaller step or "
                         "zeno_min_interval follows such events",
                         i, name, b, interval, s->fire_count + 1, s->last_interval);
    }
    return 0;
}

/* Signs after a handling round; marks the cascading crossings in w->next. */
static int settle_signs(ssx_system *sys, double b, const event_bracket *br, instant_work *w)
{
    int need_probe = 0;
    for (int i = 0; i < sys->n_indicators; ++i) {
        w->z_after[i] = sys->indicator_states[i].value;
        w->turned_back[i] = 0;
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        need_probe |= near_zero(w, i);
    }
    /* the probe stays well inside the macro step it belongs to */
    double delta_max =
        fmax(distinct_events_interval(&sys->hybrid), PROBE_HORIZON * (br->t_end - br->a0));
    if (need_probe && probe(sys, b, delta_max, w) != 0) {
        return -1;
    }
    for (int i = 0; i < sys->n_indicators; ++i) {
        const ssx_indicator *ind = &sys->indicators[i];
        indicator_state *s = &sys->indicator_states[i];
        /* a fired indicator still within its residue band goes where the probe says; any other
         * sign change was made by the handling itself */
        int from_probe = near_zero(w, i);
        double z = from_probe ? w->z_probe[i] : w->z_after[i];
        int new_sign = sign_of(z, s->sign);
        /* Turned back towards its near side yet unable to leave the far one: the handled state
         * cannot climb out of the residue at b (a ball too slow to leave the floor) and would
         * sink unseen. That is the end of a Zeno sequence. */
        if (from_probe && new_sign == s->sign && w->turned_back[i]) {
            return fail_zeno(sys, ind->component, i, b,
                             "indicator %d of component '%s' cannot leave zero after its event "
                             "at t=%.17g (event number %ld): the handled state turns back but "
                             "stays within the residue %.3g; chattering (Zeno) behaviour",
                             i, sys->components[ind->component]->name, b, s->fire_count,
                             fabs(w->z_after[i]));
        }
        /* a handler that moves a fired indicator back across is a new crossing; one that
         * moves an indicator resting on zero from an earlier instant only ends the rest */
        int resting = s->on_zero && !w->fired[i];
        w->next[i] = 0;
        if (s->sign != 0 && new_sign != s->sign && !from_probe && !resting) {
            int crossing = new_sign > 0 ? 1 : -1;
            w->next[i] = ind->direction == 0 || ind->direction == crossing;
        }
        s->sign = new_sign;
        s->on_zero = s->on_zero && z == 0.0;
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
        indicator_state *s = &sys->indicator_states[i];
        w->fired[i] = fires_now(sys, i);
        indicator_follow(s, s->value);
        w->band[i] = residue_band(sys, br, &workspace(sys)->brackets[i], s->value);
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
            indicator_state *s = &sys->indicator_states[i];
            if (!w->fired[i]) {
                continue;
            }
            if (micro == 0) {
                s->last_interval = s->fired_before ? b - s->last_event_time : INFINITY;
            }
            s->fired_before = 1;
            s->last_event_time = b;
            s->fire_count++;
        }
        sys->stats.events++;
        if (event_sources_notify_indicators(sys, w->fired, w->listened, b) != 0 ||
            coupling_settle(sys, b) != 0 ||
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
    if (!workspace(sys)->zero_start_pending) {
        return 0;
    }
    workspace(sys)->zero_start_pending = 0;
    int unknown = 0;
    for (int i = 0; i < sys->n_indicators; ++i) {
        unknown |= sys->indicator_states[i].sign == 0;
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
        const indicator_state *s = &sys->indicator_states[i];
        workspace(sys)->brackets[i].z_left = workspace(sys)->brackets[i].z_right = s->value;
        w.fired[i] = s->sign == 0;
        w.z_after[i] = s->value;
        w.band[i] = 0.0;
    }
    int status =
        probe(sys, a0, fmax(distinct_events_interval(&sys->hybrid), PROBE_HORIZON * (t_next - a0)),
              &w);
    int fires = 0;
    for (int i = 0; status == 0 && i < sys->n_indicators; ++i) {
        indicator_state *s = &sys->indicator_states[i];
        int direction = sys->indicators[i].direction;
        if (s->sign != 0 || w.z_probe[i] == 0.0) {
            continue;
        }
        int going = w.z_probe[i] > 0.0 ? 1 : -1;
        int crossing = direction == 0 || direction == going;
        /* a crossing starts on the near side, so that the zero at a0 counts as the far one */
        s->sign = crossing ? -going : going;
        fires |= crossing;
    }
    if (status == 0 && fires) {
        sys->time = a0;
        status = handle_instant(sys, &br, &w, 0);
    }
    work_free(&w);
    return status;
}

int hybrid_prepare(ssx_system *sys, void **out)
{
    size_t n = (size_t)sys->n_indicators;
    indicator_state *states = realloc(sys->indicator_states, n * sizeof *states);
    if (states != NULL) {
        sys->indicator_states = states;
    }
    hybrid_workspace *hw = calloc(1, sizeof *hw);
    indicator_bracket *brackets = hw != NULL ? calloc(n > 0 ? n : 1, sizeof *brackets) : NULL;
    size_t n_components = (size_t)sys->n_components;
    size_t *own_pending =
        brackets != NULL ? calloc(n_components > 0 ? n_components : 1, sizeof *own_pending) : NULL;
    if (states == NULL || own_pending == NULL) {
        free(brackets);
        free(hw);
        return fail(sys, -1, -1, sys->time, "out of memory preparing %zu event indicators", n);
    }
    memset(states, 0, n * sizeof *states);
    *hw = (hybrid_workspace){
        .brackets = brackets, .zero_start_pending = 1, .own_pending = own_pending};
    *out = hw;
    return 0;
}

/* The system at t, where no indicator crosses: the indicators' sides follow their values. */
static int pass_without_event(ssx_system *sys, double t, double *reached)
{
    for (int i = 0; i < sys->n_indicators; ++i) {
        indicator_follow(&sys->indicator_states[i], sys->indicator_states[i].value);
    }
    sys->time = t;
    *reached = t;
    return event_sources_commit_own(sys, t);
}

int hybrid_begin_piece(ssx_system *sys, double a0, double t_end, hybrid_piece *piece)
{
    sys->time = a0;
    if (resolve_zero_start(sys, a0, t_end) != 0) {
        return -1;
    }
    *piece = (hybrid_piece){.a0 = a0,
                            .do_steps_before = sys->stats.do_step_calls,
                            .restores_before = sys->stats.state_restores};
    for (int i = 0; i < sys->n_indicators; ++i) {
        workspace(sys)->brackets[i].z_left = sys->indicator_states[i].value;
    }
    for (int i = 0; i < sys->n_components; ++i) {
        workspace(sys)->own_pending[i] = own_events_pending_count(sys->components[i]);
    }
    return 0;
}

/* Where the piece must end because a component reported an event at a known time: an output
 * clock's tick that a listener waits for, or (ssx_set_stop_at_own_events) any own event. */
static int earliest_stop(const ssx_system *sys, double *t, int *at_step_end)
{
    int found = event_sources_earliest_tick(sys, t, at_step_end);
    double own;
    if (sys->own_event_stops && own_events_earliest(sys, &own) && (!found || own < *t)) {
        *t = own;
        *at_step_end = 0;
        found = 1;
    }
    return found;
}

/* The system back at the piece's start a0 (keeping the events pending there), stepped to t. */
static int step_again_to(ssx_system *sys, double a0, double t)
{
    if (run_interrupted(sys, a0) != 0 || system_restore(sys, MACRO_SLOT, a0) != 0) {
        return -1;
    }
    /* the restore keeps the events at a0: those the step just undone reported there go */
    for (int i = 0; i < sys->n_components; ++i) {
        own_events_keep_first(sys->components[i], workspace(sys)->own_pending[i]);
    }
    return coupling_step(sys, a0, t - a0);
}

/* A listened tick reported at the end of the step to *t_end by an FMU that cannot return
 * early happened somewhere in (a0, *t_end]: a tick is a yes or no, so the whole system is
 * stepped again from a0 to the bracket's middle until the bracket is within tol_time, and
 * ends at its far end, where the tick is then reported. Each trial counts as a localization
 * iteration, its restore as a rollback. */
static int bisect_tick_at_step_end(ssx_system *sys, double a0, double *t_end)
{
    double a = a0, b = *t_end;
    int stepped_to_b = 1;
    for (int iterations = 0; b - a > sys->hybrid.tol_time; ++iterations) {
        if (iterations == sys->hybrid.max_iterations) {
            return fail(sys, -1, -1, a0,
                        "an output clock's tick reported at a step's end was not bracketed "
                        "within tol_time=%g in %d steps from t=%.17g (bracket [%.17g, %.17g])",
                        sys->hybrid.tol_time, iterations, a0, a, b);
        }
        double middle = a + 0.5 * (b - a);
        if (step_again_to(sys, a0, middle) != 0) {
            return -1;
        }
        sys->stats.localization_iterations++;
        double tick;
        int at_step_end;
        stepped_to_b = earliest_stop(sys, &tick, &at_step_end) && tick > a0 && tick <= middle;
        if (stepped_to_b) {
            b = middle;
        } else {
            a = middle;
        }
    }
    if (!stepped_to_b && step_again_to(sys, a0, b) != 0) {
        return -1;
    }
    *t_end = b;
    return 0;
}

/* An output clock's tick that a listener waits for, reported at the end of a step by an FMU
 * that cannot return early, is first bracketed by bisection (bisect_tick_at_step_end).
 * One reported inside the piece at a known time (its FMU returned early there): the whole
 * system goes back to the piece's start a0 and steps
 * to that time, which ends the piece (*t_end), so the tick reaches its listeners there. No
 * localization: the time is known. An FMU that finds its event by the sign of a value may end
 * the step to the tick a rounding short of it: then once more, a rounding past it (a thousandth
 * of half tol_time). One that still ticks only at the next piece's start gets a step of half
 * tol_time there: every step back advances, and a tick is handled at most that late. */
static int step_to_clock_tick(ssx_system *sys, double a0, double *t_end)
{
    double lead = 0.5 * sys->hybrid.tol_time;
    int went_past = 0, bisected = 0;
    for (int tries = 0;; ++tries) {
        double tick, target;
        int at_step_end = 0;
        if (earliest_stop(sys, &tick, &at_step_end) && at_step_end && !bisected &&
            tick - a0 > sys->hybrid.tol_time) {
            bisected = 1;
            if (bisect_tick_at_step_end(sys, a0, t_end) != 0) {
                return -1;
            }
            continue;
        }
        if (earliest_stop(sys, &tick, &at_step_end)) {
            target = fmax(tick, a0 + lead);
            if (target > *t_end - lead) {
                /* at the piece's end, within the tolerance */
                return 0;
            }
        } else if (tries > 0 && !went_past) {
            went_past = 1;
            tick = *t_end;
            target = tick + fmax(1e-3 * lead, 4.0 * DBL_EPSILON * fabs(tick));
        } else {
            return 0;
        }
        if (tries == sys->hybrid.max_iterations) {
            return fail(sys, -1, -1, a0,
                        "an output clock's tick moved at each of %d steps back from t=%.17g "
                        "(now at t=%.17g): its FMU reports another time each time",
                        tries, a0, tick);
        }
        if (step_again_to(sys, a0, target) != 0) {
            return -1;
        }
        *t_end = target;
    }
}

int hybrid_end_piece(ssx_system *sys, const hybrid_piece *piece, double t_end, double grid_step,
                     double *reached, int *event)
{
    *event = 0;
    double step_end = t_end;
    if (step_to_clock_tick(sys, piece->a0, &t_end) != 0 ||
        indicators_evaluate(sys, t_end) != 0) {
        return -1;
    }
    if (!any_fires(sys)) {
        long own_before = sys->stats.own_events;
        if (pass_without_event(sys, t_end, reached) != 0) {
            return -1;
        }
        /* a piece cut at a member's own event ends the step there, its sample after the event
         * recorded as an indicator event's is */
        if (sys->own_event_stops && t_end < step_end && sys->stats.own_events > own_before) {
            *event = 1;
            return record_sample(sys, t_end, 0);
        }
        return 0;
    }
    event_bracket br = {.a0 = piece->a0,
                        .t_end = t_end,
                        .grid_step = grid_step,
                        .do_steps_before = piece->do_steps_before,
                        .restores_before = piece->restores_before};
    if (locate(sys, &br) != 0) {
        return -1;
    }
    if (!any_fires(sys)) {
        /* the trajectory through the final near end has not crossed by b: no event up to b,
         * and the piece goes on from there */
        return pass_without_event(sys, br.b, reached);
    }
    if (event_sources_commit_own(sys, br.b) != 0) {
        return -1;
    }
    sys->time = br.b;
    instant_work w;
    if (work_init(&w, sys, br.b) != 0) {
        return -1;
    }
    int status = handle_instant(sys, &br, &w, 1);
    work_free(&w);
    *reached = br.b;
    *event = 1;
    return status;
}

void hybrid_carry_out(const ssx_system *sys, double *carried)
{
    const hybrid_workspace *hw = sys->algorithm_workspace;
    carried[0] = hw != NULL ? hw->zero_start_pending : 0.0;
}

void hybrid_carry_in(ssx_system *sys, const double *carried)
{
    hybrid_workspace *hw = sys->algorithm_workspace;
    if (hw != NULL) {
        hw->zero_start_pending = carried[0] != 0.0;
    }
}

void hybrid_release(ssx_system *sys, void *workspace)
{
    (void)sys;
    hybrid_workspace *hw = workspace;
    if (hw != NULL) {
        free(hw->brackets);
        free(hw->own_pending);
        free(hw);
    }
}

int hybrid_step(ssx_system *sys, double t, double from, double t_next, int *event_out)
{
    double a0 = from;
    *event_out = 0;
    while (a0 < t_next) {
        hybrid_piece piece;
        if (run_interrupted(sys, a0) != 0 || hybrid_begin_piece(sys, a0, t_next, &piece) != 0 ||
            system_snapshot(sys, MACRO_SLOT) != 0 || coupling_step(sys, a0, t_next - a0) != 0) {
            return -1;
        }
        sys->stats.macro_steps++;
        double reached;
        int event;
        if (hybrid_end_piece(sys, &piece, t_next, t_next - t, &reached, &event) != 0) {
            return -1;
        }
        if (!event && reached == t_next) {
            return record_grid_point(sys, t_next);
        }
        if (event) {
            *event_out = 1;
            return 0;
        }
        a0 = reached;
    }
    return 0;
}
