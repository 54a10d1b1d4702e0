#include "input_order.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "component_calls.h"
#include "energy_residual.h"
#include "error.h"
#include "input_links.h"

/* Communication points kept per component: three give a second-order extrapolation. */
enum { HISTORY = 3 };

typedef struct {
    double t[HISTORY];   /* newest first */
    double *y[HISTORY];  /* the outputs at t[k] */
    int count;
    double *slope;       /* output derivatives at the step's start, told by the component */
    int has_slope;
    /* per input its first and second time derivative over the coming step; NULL while the
     * component's inputs are held at their value at the step's start */
    double *input_derivatives;
    int holds_mean; /* it cannot interpolate: its inputs are held at the polynomials' mean */
    int order;      /* the input derivative order it is given: the system's, lower once refused */
    double order_refused_at;  /* NaN: it took every order it was given */
    double slopes_failed_at;  /* its output derivatives were non-finite there; NaN: never */
} component_track;

struct input_motion {
    int n_components; /* as prepared */
    int order;
    int stepping; /* inside a coupled step from t over h */
    double t;
    double h;
    double error; /* of the last coupled step */
    int (*base_step)(ssx_system *sys, double t, double h);
    component_track *tracks;
    unsigned char *interpolated; /* per connection: its driver steps first (Gauss-Seidel) */
    unsigned char *held;         /* per component: a loop member, its inputs held */
    /* measured before the loops were solved (input_order_measure_loop): the largest weighted
     * coupling error of the loops' inputs, and per power bond its residual (NaN: not yet) */
    double loop_error;
    double *bond_error;
    int n_bonds;
};

static int tracked_step(ssx_system *sys, double t, double h);

void input_order_free(ssx_system *sys)
{
    struct input_motion *w = sys->input_motion;
    if (w == NULL) {
        return;
    }
    for (int i = 0; i < w->n_components; ++i) {
        component_track *tr = &w->tracks[i];
        for (int k = 0; k < HISTORY; ++k) {
            free(tr->y[k]);
        }
        free(tr->slope);
        free(tr->input_derivatives);
    }
    free(w->tracks);
    free(w->interpolated);
    free(w->held);
    free(w->bond_error);
    free(w);
    sys->input_motion = NULL;
}

static int has_real_input(const ssx_component *c)
{
    for (int i = 0; i < c->n_inputs; ++i) {
        if (c->input_ports[i].type == SSX_REAL) {
            return 1;
        }
    }
    return 0;
}

static int has_real_output(const ssx_component *c)
{
    for (int i = 0; i < c->n_outputs; ++i) {
        if (c->output_ports[i].type == SSX_REAL) {
            return 1;
        }
    }
    return 0;
}

static int interpolates(const ssx_system *sys, const ssx_component *c)
{
    return sys->input_order > 0 && c->ops->set_input_derivatives != NULL &&
           c->ops->capabilities(c).can_interpolate_inputs && has_real_input(c);
}

/* Whether the component tells its outputs' time derivatives. */
static int tells_output_derivatives(const ssx_component *c)
{
    return c->ops->output_derivatives != NULL &&
           c->ops->capabilities(c).max_output_derivative_order >= 1;
}

/* A co-simulation FMU that holds its inputs, each at its polynomial's mean over the step. */
static int holds_extrapolated(const ssx_system *sys, const ssx_component *c)
{
    return sys->input_order > 0 && sys->extrapolate_held_inputs &&
           c->ops->set_input_derivatives != NULL &&
           !c->ops->capabilities(c).can_interpolate_inputs && has_real_input(c);
}

static int prepare_track(ssx_system *sys, struct input_motion *w, int i)
{
    ssx_component *c = sys->components[i];
    component_track *tr = &w->tracks[i];
    size_t n_out = (size_t)c->n_outputs + 1;
    for (int k = 0; k < HISTORY; ++k) {
        tr->y[k] = calloc(n_out, sizeof(double));
        if (tr->y[k] == NULL) {
            return -1;
        }
    }
    tr->slope = calloc(n_out, sizeof(double));
    if (tr->slope == NULL) {
        return -1;
    }
    tr->holds_mean = holds_extrapolated(sys, c);
    tr->order = sys->input_order;
    tr->order_refused_at = NAN;
    tr->slopes_failed_at = NAN;
    if (!tr->holds_mean && !interpolates(sys, c)) {
        return 0;
    }
    tr->input_derivatives = calloc(2 * (size_t)c->n_inputs + 1, sizeof(double));
    return tr->input_derivatives == NULL ? -1 : 0;
}

/* Which connections interpolate (their driver steps before the input's owner in the same
 * Gauss-Seidel step) and which components are loop members. */
static void classify(ssx_system *sys, struct input_motion *w, int *position)
{
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        const ssx_group *g = &sys->groups[gi];
        for (int m = 0; m < g->size; ++m) {
            int c = sys->order[g->first + m];
            position[c] = gi;
            w->held[c] = (unsigned char)g->is_loop;
        }
    }
    for (int k = 0; k < sys->n_connections; ++k) {
        const ssx_connection *cn = &sys->connections[k];
        w->interpolated[k] = sys->coupling == SSX_GAUSS_SEIDEL &&
                             position[cn->src_component] < position[cn->dst_component];
    }
}

/* A String or Binary value is a number of the system's table: no distance to weigh. */
static int measurable(const ssx_port *port)
{
    return port->type != SSX_STRING && port->type != SSX_BINARY;
}

static void count_unmeasured(ssx_system *sys)
{
    if (!sys->step_control.enabled || sys->step_control.energy) {
        return;
    }
    for (int ci = 0; ci < sys->n_components; ++ci) {
        const ssx_component *c = sys->components[ci];
        for (int i = 0; i < c->n_inputs; ++i) {
            sys->stats.unmeasured_inputs += c->input_driver[i] >= 0 &&
                                            !measurable(&c->input_ports[i]);
        }
    }
}

int input_order_prepare(ssx_system *sys)
{
    input_order_free(sys);
    sys->write_input_derivatives = input_order_write;
    if (sys->input_order == 0 && !sys->step_control.enabled) {
        return 0;
    }
    struct input_motion *w = calloc(1, sizeof *w);
    int *position = malloc(((size_t)sys->n_components + 1) * sizeof *position);
    if (w != NULL) {
        w->tracks = calloc((size_t)sys->n_components + 1, sizeof *w->tracks);
        w->interpolated = calloc((size_t)sys->n_connections + 1, 1);
        w->held = calloc((size_t)sys->n_components + 1, 1);
        w->bond_error = calloc((size_t)sys->n_power_bonds + 1, sizeof *w->bond_error);
        w->n_bonds = sys->n_power_bonds;
    }
    sys->input_motion = w;
    if (w != NULL) {
        w->n_components = sys->n_components;
    }
    int ok = w != NULL && position != NULL && w->tracks != NULL && w->interpolated != NULL &&
             w->held != NULL && w->bond_error != NULL;
    for (int i = 0; ok && i < sys->n_components; ++i) {
        ok = prepare_track(sys, w, i) == 0;
    }
    if (!ok) {
        free(position);
        input_order_free(sys);
        return fail(sys, -1, -1, sys->time, "out of memory preparing the input order");
    }
    classify(sys, w, position);
    free(position);
    count_unmeasured(sys);
    if (sys->step_control.enabled && sys->step_control.energy &&
        energy_residual_check(sys) != 0) {
        input_order_free(sys);
        return -1;
    }
    w->order = sys->input_order;
    w->base_step = sys->coupled_step;
    sys->coupled_step = tracked_step;
    return 0;
}

void input_order_forget(ssx_system *sys)
{
    struct input_motion *w = sys->input_motion;
    if (w == NULL) {
        return;
    }
    for (int i = 0; i < sys->n_components; ++i) {
        w->tracks[i].count = 0;
        w->tracks[i].has_slope = 0;
    }
}

double input_order_error(const ssx_system *sys)
{
    return sys->input_motion != NULL ? sys->input_motion->error : 0.0;
}

/* The outputs at t become the newest history point; points at or after t (a step taken again
 * after a restore) are dropped first. */
static void remember(component_track *tr, const ssx_component *c, double t)
{
    double tiny = 1e-12 * fmax(1.0, fabs(t));
    while (tr->count > 0 && tr->t[0] >= t - tiny) {
        double *y = tr->y[0];
        memmove(&tr->t[0], &tr->t[1], (HISTORY - 1) * sizeof tr->t[0]);
        memmove(&tr->y[0], &tr->y[1], (HISTORY - 1) * sizeof tr->y[0]);
        tr->y[HISTORY - 1] = y;
        tr->count--;
    }
    double *y = tr->y[HISTORY - 1];
    memmove(&tr->t[1], &tr->t[0], (HISTORY - 1) * sizeof tr->t[0]);
    memmove(&tr->y[1], &tr->y[0], (HISTORY - 1) * sizeof tr->y[0]);
    tr->t[0] = t;
    tr->y[0] = y;
    memcpy(y, c->outputs, (size_t)c->n_outputs * sizeof(double));
    if (tr->count < HISTORY) {
        tr->count++;
    }
}

/* Output derivatives that are NaN or infinite (as some exported FMUs tell) are never handed
 * on: from then on the component's slopes come from its communication points. */
static int read_slopes(ssx_system *sys, ssx_component *c, component_track *tr, double t)
{
    tr->has_slope = 0;
    if (!tells_output_derivatives(c) || !has_real_output(c) || !isnan(tr->slopes_failed_at)) {
        return 0;
    }
    if (c->ops->output_derivatives(sys, c, t, tr->slope) != 0) {
        return -1;
    }
    for (int o = 0; o < c->n_outputs; ++o) {
        if (c->output_ports[o].type == SSX_REAL && !isfinite(tr->slope[o])) {
            tr->slopes_failed_at = t;
            sys->stats.output_derivative_fallbacks++;
            return 0;
        }
    }
    tr->has_slope = 1;
    return 0;
}

/* The history and the output derivatives at the step's start, in schedule order: each FMU
 * gets its inputs' values and derivatives at t first, so its direct-feedthrough outputs are
 * those of the drivers' outputs at t (under Jacobi they were computed from the inputs the last
 * step extrapolated to t: an offset no shorter step could shrink) and move with its inputs. */
static int begin_step(ssx_system *sys, struct input_motion *w, double t, double h)
{
    w->stepping = 0;
    for (int i = 0; i < sys->n_components; ++i) {
        remember(&w->tracks[i], sys->components[i], t);
    }
    for (int s = 0; s < sys->n_components; ++s) {
        int i = sys->order[s];
        ssx_component *c = sys->components[i];
        component_track *tr = &w->tracks[i];
        if (c->ops->set_input_derivatives == NULL) {
            continue; /* a kind whose inputs never move over a step */
        }
        if (!w->held[i] && c->n_inputs > 0) {
            input_links_apply(c);
            input_order_propagate(sys, c);
            if (component_write_inputs(sys, c) != 0 || component_read_outputs(sys, c) != 0) {
                return -1;
            }
            memcpy(tr->y[0], c->outputs, (size_t)c->n_outputs * sizeof(double));
        }
        if (w->order > 0 && read_slopes(sys, c, tr, t) != 0) {
            return -1;
        }
    }
    w->stepping = 1;
    w->t = t;
    w->h = h;
    return 0;
}

/* Derivatives at the newest point from the older history points (Newton's divided
 * differences); d2 only for order 2 with three points. */
static void history_slope(const component_track *tr, int output, double t, double y, int order,
                          double *d1, double *d2)
{
    double tiny = 1e-12 * fmax(1.0, fabs(t));
    int k = 0;
    while (k < tr->count && tr->t[k] >= t - tiny) {
        ++k; /* the point at t itself is y */
    }
    *d1 = *d2 = 0.0;
    if (k >= tr->count) {
        return;
    }
    double t1 = tr->t[k], y1 = tr->y[k][output];
    double f01 = (y - y1) / (t - t1);
    *d1 = f01;
    if (order < 2 || k + 1 >= tr->count) {
        return;
    }
    double t2 = tr->t[k + 1], y2 = tr->y[k + 1][output];
    double f12 = (y1 - y2) / (t1 - t2);
    double f012 = (f01 - f12) / (t - t2);
    *d1 = f01 + f012 * (t - t1);
    *d2 = 2.0 * f012;
}

/* Driver output `output` of component `src` over the coming step: its value at the step's
 * start and derivatives there. */
static double driver_polynomial(const ssx_system *sys, const struct input_motion *w,
                                int connection, double *d1, double *d2)
{
    const ssx_connection *cn = &sys->connections[connection];
    const ssx_component *src = sys->components[cn->src_component];
    const component_track *tr = &w->tracks[cn->src_component];
    int o = cn->src_output;
    double y = src->outputs[o];
    int real = src->output_ports[o].type == SSX_REAL;
    *d1 = *d2 = 0.0;
    if (!real) {
        return y;
    }
    if (w->stepping && w->interpolated[connection] && tr->count > 0) {
        /* the driver is already at t + h: interpolate between its outputs at t and t + h */
        double y0 = tr->y[0][o], h = w->h;
        double secant = (y - y0) / h;
        *d1 = secant;
        if (w->order >= 2 && tr->count > 1) {
            double back = (y0 - tr->y[1][o]) / (tr->t[0] - tr->t[1]);
            double curvature = (secant - back) / (h + tr->t[0] - tr->t[1]);
            *d1 = secant - curvature * h;
            *d2 = 2.0 * curvature;
        }
        return y0;
    }
    double t = w->stepping ? w->t : tr->count > 0 ? tr->t[0] : 0.0;
    if (tr->has_slope) {
        *d1 = tr->slope[o];
        if (w->order >= 2 && tr->count > 1 && w->stepping) {
            /* the second derivative that puts the previous point on the parabola */
            double dt = tr->t[1] - t;
            *d2 = 2.0 * (tr->y[1][o] - y - *d1 * dt) / (dt * dt);
        }
        return y;
    }
    history_slope(tr, o, t, y, w->order, d1, d2);
    return y;
}

void input_order_propagate(ssx_system *sys, ssx_component *c)
{
    struct input_motion *w = sys->input_motion;
    if (w == NULL || w->tracks[c->index].input_derivatives == NULL) {
        return;
    }
    int held = w->held[c->index];
    const component_track *tr = &w->tracks[c->index];
    double *derivatives = tr->input_derivatives;
    /* inside the step, an FMU that holds its inputs gets each polynomial's mean over it */
    double mean_at = w->stepping && tr->holds_mean ? w->h : 0.0;
    for (int i = 0; i < c->n_inputs; ++i) {
        double *d = &derivatives[2 * i];
        int k = c->input_driver[i];
        d[0] = d[1] = 0.0;
        if (k < 0 || held || c->input_ports[i].type != SSX_REAL) {
            continue;
        }
        const ssx_connection *cn = &sys->connections[k];
        double d1, d2;
        double y = driver_polynomial(sys, w, k, &d1, &d2);
        c->inputs[i] = cn->scale * y + cn->offset;
        d[0] = tr->order >= 1 ? cn->scale * d1 : 0.0;
        d[1] = tr->order >= 2 ? cn->scale * d2 : 0.0;
        c->inputs[i] += mean_at * (0.5 * d[0] + mean_at * d[1] / 6.0);
    }
}

/* One order lower for good: the derivatives beyond it are dropped (at 0 the inputs are held
 * at their values at the step's start). */
static void lower_input_order(ssx_system *sys, ssx_component *c, component_track *tr)
{
    tr->order--;
    for (int i = 0; i < c->n_inputs; ++i) {
        for (int k = tr->order; k < 2; ++k) {
            tr->input_derivatives[2 * i + k] = 0.0;
        }
    }
    if (isnan(tr->order_refused_at)) {
        tr->order_refused_at = sys->time;
        sys->stats.input_order_fallbacks++;
    }
}

int input_order_write(ssx_system *sys, ssx_component *c)
{
    struct input_motion *w = sys->input_motion;
    if (w == NULL || w->tracks[c->index].input_derivatives == NULL) {
        return 0;
    }
    component_track *tr = &w->tracks[c->index];
    if (tr->holds_mean) {
        return 0; /* it holds its inputs (extrapolated) */
    }
    /* an FMU that refuses an order (FMUs that take first derivatives only refuse the second)
     * is offered the next lower one */
    while (tr->order > 0) {
        int status = c->ops->set_input_derivatives(sys, c, tr->order, tr->input_derivatives);
        if (status <= 0) {
            return status;
        }
        lower_input_order(sys, c, tr);
    }
    return 0;
}

int ssx_coupling_fallbacks(const ssx_system *sys, ssx_coupling_fallback *out, int max)
{
    const struct input_motion *w = sys->input_motion;
    int count = 0;
    for (int i = 0; w != NULL && i < w->n_components; ++i) {
        const component_track *tr = &w->tracks[i];
        if (isnan(tr->order_refused_at) && isnan(tr->slopes_failed_at)) {
            continue;
        }
        if (count < max && out != NULL) {
            out[count] = (ssx_coupling_fallback){.component = i,
                                                 .input_order = tr->order,
                                                 .input_order_time = tr->order_refused_at,
                                                 .output_derivatives_time = tr->slopes_failed_at};
        }
        count++;
    }
    return count;
}

/* After the step: each input at the value its polynomial reached at t + h (what an
 * interpolating FMU holds; one that holds its inputs kept the mean), and the coupling error
 * against the drivers' outputs there. */
static double end_step(ssx_system *sys, struct input_motion *w)
{
    double h = w->h, error = 0.0;
    int energy = sys->step_control.enabled && sys->step_control.energy;
    int measured = sys->step_control.enabled && !energy;
    double rtol = sys->step_control.rtol, atol = sys->step_control.atol;
    for (int ci = 0; ci < sys->n_components; ++ci) {
        ssx_component *c = sys->components[ci];
        if (w->held[ci]) {
            continue;
        }
        /* from the polynomial's mean (a held input) or its start to its value at t + h */
        int mean_held = w->tracks[ci].holds_mean;
        double moved = mean_held ? 0.5 : 1.0;
        double rest = mean_held ? 1.0 / 3.0 : 0.5;
        for (int i = 0; i < c->n_inputs; ++i) {
            int k = c->input_driver[i];
            if (k < 0) {
                continue;
            }
            if (w->tracks[ci].input_derivatives != NULL) {
                const double *d = &w->tracks[ci].input_derivatives[2 * i];
                c->inputs[i] += h * (moved * d[0] + rest * h * d[1]);
            }
            const ssx_connection *cn = &sys->connections[k];
            if (!measured || !measurable(&c->input_ports[i])) {
                continue;
            }
            double y = cn->scale * sys->components[cn->src_component]->outputs[cn->src_output] +
                       cn->offset;
            double weighted = fabs(y - c->inputs[i]) / (atol + rtol * fabs(y));
            error = weighted > error ? weighted : error;
        }
    }
    w->stepping = 0;
    return energy ? energy_residual_error(sys, h, w->bond_error) : fmax(error, w->loop_error);
}

/* The weighted difference between what a driven Real input was given over the step and
 * what its driver produced at its end. */
static double input_error(const ssx_system *sys, const ssx_component *c, int input)
{
    const ssx_connection *cn = &sys->connections[c->input_driver[input]];
    double y = cn->scale * sys->components[cn->src_component]->outputs[cn->src_output] +
               cn->offset;
    const ssx_step_control *sc = &sys->step_control;
    return fabs(y - c->inputs[input]) / (sc->atol + sc->rtol * fabs(y));
}

void input_order_measure_loop(ssx_system *sys, const ssx_group *g)
{
    struct input_motion *w = sys->input_motion;
    if (w == NULL || !w->stepping || !sys->step_control.enabled) {
        return;
    }
    if (sys->step_control.energy) {
        for (int b = 0; b < w->n_bonds && b < sys->n_power_bonds; ++b) {
            const int *end = &sys->power_bonds[4 * b];
            for (int m = 0; m < g->size; ++m) {
                int member = sys->order[g->first + m];
                if (member == end[0] || member == end[2]) {
                    w->bond_error[b] = energy_residual_bond(sys, b, w->h);
                    break;
                }
            }
        }
        return;
    }
    for (int m = 0; m < g->size; ++m) {
        const ssx_component *c = sys->components[sys->order[g->first + m]];
        for (int i = 0; i < c->n_inputs; ++i) {
            if (c->input_driver[i] >= 0 && c->input_ports[i].type == SSX_REAL) {
                w->loop_error = fmax(w->loop_error, input_error(sys, c, i));
            }
        }
    }
}

static int tracked_step(ssx_system *sys, double t, double h)
{
    struct input_motion *w = sys->input_motion;
    w->loop_error = 0.0;
    for (int b = 0; b < w->n_bonds; ++b) {
        w->bond_error[b] = NAN;
    }
    if (begin_step(sys, w, t, h) != 0) {
        w->stepping = 0;
        return -1;
    }
    int status = w->base_step(sys, t, h);
    w->error = end_step(sys, w);
    return status;
}

/* Per component: the history's times and count, its input order and when orders and slopes
 * failed, then its outputs at each history point. */
static size_t track_size(const ssx_component *c)
{
    return HISTORY + 4 + HISTORY * (size_t)c->n_outputs;
}

size_t input_order_state_size(const ssx_system *sys)
{
    const struct input_motion *w = sys->input_motion;
    size_t n = 0;
    for (int i = 0; w != NULL && i < w->n_components; ++i) {
        n += track_size(sys->components[i]);
    }
    return n;
}

void input_order_state_save(const ssx_system *sys, double *values)
{
    const struct input_motion *w = sys->input_motion;
    for (int i = 0; w != NULL && i < w->n_components; ++i) {
        const component_track *tr = &w->tracks[i];
        size_t n_out = (size_t)sys->components[i]->n_outputs;
        memcpy(values, tr->t, sizeof tr->t);
        values += HISTORY;
        *values++ = tr->count;
        *values++ = tr->order;
        *values++ = tr->order_refused_at;
        *values++ = tr->slopes_failed_at;
        for (int k = 0; k < HISTORY; ++k, values += n_out) {
            memcpy(values, tr->y[k], n_out * sizeof(double));
        }
    }
}

void input_order_state_restore(ssx_system *sys, const double *values)
{
    struct input_motion *w = sys->input_motion;
    for (int i = 0; w != NULL && i < w->n_components; ++i) {
        component_track *tr = &w->tracks[i];
        size_t n_out = (size_t)sys->components[i]->n_outputs;
        memcpy(tr->t, values, sizeof tr->t);
        values += HISTORY;
        tr->count = (int)*values++;
        tr->order = (int)*values++;
        tr->order_refused_at = *values++;
        tr->slopes_failed_at = *values++;
        for (int k = 0; k < HISTORY; ++k, values += n_out) {
            memcpy(tr->y[k], values, n_out * sizeof(double));
        }
    }
}
