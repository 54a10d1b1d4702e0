#include "adaptive.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "coupling.h"
#include "error.h"
#include "hybrid.h"
#include "input_order.h"
#include "interrupt.h"
#include "event_source.h"
#include "recording.h"
#include "system_state.h"

/* Errors below this count as this small: the growth factor stays finite. */
#define SMALLEST_ERROR 1e-10

struct adaptive_workspace {
    double proposed; /* the next step's length; 0 before the first */
    double previous_error; /* of the last accepted step (the PI controller's); 0 before one */
};

static void controller_free(ssx_system *sys)
{
    free(sys->adaptive);
    sys->adaptive = NULL;
}

int adaptive_prepare(ssx_system *sys, void **workspace)
{
    controller_free(sys);
    sys->adaptive = calloc(1, sizeof *sys->adaptive);
    if (sys->adaptive == NULL) {
        return fail(sys, -1, -1, sys->time, "out of memory preparing the step control");
    }
    if (sys->stepping_hybrid) {
        return hybrid_prepare(sys, workspace);
    }
    return 0;
}

void adaptive_release(ssx_system *sys, void *workspace)
{
    controller_free(sys);
    hybrid_release(sys, workspace);
}

void adaptive_carry_out(const ssx_system *sys, double *carried)
{
    hybrid_carry_out(sys, carried);
    carried[1] = sys->adaptive->proposed;
    carried[2] = sys->adaptive->previous_error;
}

void adaptive_carry_in(ssx_system *sys, const double *carried)
{
    hybrid_carry_in(sys, carried);
    sys->adaptive->proposed = carried[1];
    sys->adaptive->previous_error = carried[2];
}

/* The factor the error asks of the step, within [min_change, max_change] (a controller that
 * jumps further trusts an error estimate beyond what one step tells). The coupling error of held
 * inputs grows like h, of order-p inputs like h^(p + 1); the energy residual is under ECCO's PI
 * controller, which also weighs the error's trend since the last accepted step. */
static double step_factor(const ssx_system *sys, double error)
{
    const ssx_step_control *sc = &sys->step_control;
    double e = fmax(error, SMALLEST_ERROR);
    double factor;
    if (sc->energy) {
        double previous = sys->adaptive->previous_error > 0.0 ? sys->adaptive->previous_error : e;
        factor = sc->safety * pow(e, -(sc->integral_gain + sc->proportional_gain)) *
                 pow(previous, sc->proportional_gain);
    } else {
        factor = sc->safety * pow(e, -1.0 / (double)(sys->input_order + 1));
    }
    return fmin(sc->max_change, fmax(sc->min_change, factor));
}

/* Without an initial step: a tenth of the grid interval, shortened as the tolerance asks of
 * an error that grows like h^(order + 1) (a step taken without rollback is kept, so the first
 * one had better be within tolerance). */
static double first_step(const ssx_system *sys, double grid_step)
{
    double tolerance = fmin(1.0, fmax(sys->step_control.rtol, sys->step_control.atol));
    return 0.1 * grid_step * pow(tolerance, 1.0 / (double)(sys->input_order + 1));
}

/* A step of about h from where room is left to the grid point: within [shortest, room], and
 * all of room where the rest would be shorter than the shortest step (it would make a step
 * below min_step next). */
static double step_length(double h, double shortest, double room)
{
    h = fmin(fmax(h, shortest), room);
    return room - h < fmax(shortest, 1e-9 * room) ? room : h;
}

/* The shortest step from t: min_step, or where times are coarser than it, two of their
 * roundings (so that t + h > t: a step that vanishes in t's rounding would never end). */
static double shortest_step(const ssx_step_control *sc, double t)
{
    return fmax(sc->min_step, 2.0 * DBL_EPSILON * fabs(t));
}

static double clamp_step(const ssx_step_control *sc, double t, double h)
{
    double longest = sc->max_step > 0.0 ? sc->max_step : INFINITY;
    return fmin(longest, fmax(shortest_step(sc, t), h));
}

static void count_accepted(ssx_system *sys, double h, double error)
{
    ssx_statistics *st = &sys->stats;
    st->smallest_step = st->accepted_steps == 0 ? h : fmin(st->smallest_step, h);
    st->largest_step = fmax(st->largest_step, h);
    st->largest_error = fmax(st->largest_error, error);
    st->error_sum += error;
    st->accepted_steps++;
}

/* A step no shorter one may replace, still over the tolerance: counted, or with a strict step
 * control a failure (the result would not be what the tolerance promises). */
static int over_tolerance_at_min_step(ssx_system *sys, double a, double h, double error)
{
    if (!sys->step_control.strict) {
        sys->stats.steps_over_tolerance++;
        return 0;
    }
    return fail(sys, -1, -1, a,
                "system '%s': the step of %g from t=%.17g, at the step control's min_step=%g, "
                "still has an error of %g times the tolerance (strict step control: lower "
                "min_step, or loosen rtol and atol)",
                sys->name, h, a, sys->step_control.min_step, error);
}

/* One accepted step from a, at most to t_next; *reached is where it ends (before t_next at an
 * event). */
static int accepted_step(ssx_system *sys, double a, double t_next, double *reached, int *event)
{
    const ssx_step_control *sc = &sys->step_control;
    struct adaptive_workspace *w = sys->adaptive;
    int hybrid = sys->stepping_hybrid;
    int restorable = sc->rollback || hybrid;
    hybrid_piece piece;
    if (hybrid && hybrid_begin_piece(sys, a, t_next, &piece) != 0) {
        return -1;
    }
    double room = t_next - a;
    double shortest = shortest_step(sc, a);
    double h = step_length(w->proposed, shortest, room);
    int cut_by_grid = h < w->proposed;
    /* no shorter step may replace it: any would leave less than the shortest step behind */
    int at_limit = !(step_length(shortest, shortest, room) < h);
    double error;
    for (;;) {
        if (run_interrupted(sys, a) != 0 ||
            (restorable && system_snapshot(sys, MACRO_SLOT) != 0) ||
            coupling_step(sys, a, h) != 0) {
            return -1;
        }
        error = input_order_error(sys);
        double shorter = step_length(h * step_factor(sys, error), shortest, room);
        if (!(error > 1.0) || !sc->rollback || !(shorter < h)) {
            break;
        }
        if (system_restore(sys, MACRO_SLOT, a) != 0) {
            return -1;
        }
        sys->stats.rejected_steps++;
        h = shorter;
        at_limit = !(step_length(shortest, shortest, room) < h);
        cut_by_grid = 0;
    }
    if (error > 1.0 && at_limit && over_tolerance_at_min_step(sys, a, h, error) != 0) {
        return -1;
    }
    sys->stats.macro_steps++;
    count_accepted(sys, h, error);
    double factor = step_factor(sys, error);
    w->previous_error = fmax(error, SMALLEST_ERROR);
    /* a step the grid cut short says nothing about how long the next may grow */
    double t_end = h == room ? t_next : a + h;
    if (!(cut_by_grid && factor >= 1.0)) {
        w->proposed = clamp_step(sc, t_end, h * factor);
    }
    if (hybrid) {
        return hybrid_end_piece(sys, &piece, t_end, h, reached, event);
    }
    *reached = t_end;
    *event = 0;
    sys->time = t_end;
    return event_sources_commit_own(sys, t_end);
}

int adaptive_step(ssx_system *sys, double t, double from, double t_next, int *event_out)
{
    struct adaptive_workspace *w = sys->adaptive;
    const ssx_step_control *sc = &sys->step_control;
    if (!(w->proposed > 0.0)) {
        w->proposed = clamp_step(sc, t, sc->initial_step > 0.0 ? sc->initial_step
                                                               : first_step(sys, t_next - t));
    }
    double a = from;
    int event = 0;
    *event_out = 0;
    while (a < t_next) {
        double reached;
        if (accepted_step(sys, a, t_next, &reached, &event) != 0) {
            return -1;
        }
        if (sys->termination.component >= 0) {
            return 0;
        }
        if (event) {
            *event_out = 1;
            return 0;
        }
        a = reached;
    }
    /* an event at t_next itself recorded its samples there already */
    return event ? 0 : record_grid_point(sys, t_next);
}
