/* Newton's method with damping; a damped fixed-point iteration as fallback when Newton fails
 * (singular Jacobian, no convergence). A Jacobian column comes from the owning FMU's directional
 * derivatives when it provides them, otherwise from finite differences. */
#include "algebraic_loop.h"
#include "component_calls.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "interrupt.h"

typedef struct {
    ssx_system *sys;
    const ssx_group *group;
    double t;
    int n;
    ssx_component **owner; /* component whose input is unknown k */
    int *input;            /* its input index */
    int *analytic;         /* column k from the owner's directional derivatives */
    int *rows;             /* scratch: the unknowns driven by one component's outputs */
    unsigned int *output_vr; /* scratch: the outputs driving those unknowns */
    double *x, *r, *r_step, *x_trial, *jacobian, *dx;
} loop_work;

static int in_group(const ssx_system *sys, const ssx_group *g, int component)
{
    for (int m = 0; m < g->size; ++m) {
        if (sys->order[g->first + m] == component) {
            return 1;
        }
    }
    return 0;
}

static void work_free(loop_work *w)
{
    free(w->owner);
    free(w->input);
    free(w->analytic);
    free(w->output_vr);
    free(w->x);
    free(w->jacobian);
}

static const ssx_connection *driver_of(const loop_work *w, int k)
{
    return &w->sys->connections[w->owner[k]->input_driver[w->input[k]]];
}

/* The component's loop outputs can be differentiated by its FMU: it provides directional
 * derivatives, no Python code stands between the engine and the FMU, and they are all Real. */
static int has_directional_derivatives(const loop_work *w, const ssx_component *c)
{
    if (w->sys->loop.jacobian != SSX_JACOBIAN_AUTO || c->ops->directional_derivative == NULL ||
        c->ops->capabilities == NULL || !c->ops->capabilities(c).directional_derivatives ||
        c->hooks.evaluate_outputs != NULL) {
        return 0;
    }
    for (int k = 0; k < w->n; ++k) {
        const ssx_connection *link = driver_of(w, k);
        if (link->src_component == c->index &&
            c->output_ports[link->src_output].type != SSX_REAL) {
            return 0;
        }
    }
    return 1;
}

static int work_init(loop_work *w, ssx_system *sys, const ssx_group *g, double t)
{
    memset(w, 0, sizeof *w);
    w->sys = sys;
    w->group = g;
    w->t = t;
    int capacity = 0;
    for (int m = 0; m < g->size; ++m) {
        capacity += sys->components[sys->order[g->first + m]]->n_inputs;
    }
    size_t size = (size_t)capacity + 1;
    w->owner = malloc(size * sizeof *w->owner);
    w->input = malloc(size * sizeof *w->input);
    w->analytic = malloc(2 * size * sizeof *w->analytic);
    w->output_vr = malloc(size * sizeof *w->output_vr);
    w->x = malloc(5 * size * sizeof *w->x);
    w->jacobian = malloc(size * size * sizeof *w->jacobian);
    if (w->owner == NULL || w->input == NULL || w->analytic == NULL || w->output_vr == NULL ||
        w->x == NULL || w->jacobian == NULL) {
        work_free(w);
        return fail(sys, -1, -1, t, "out of memory solving an algebraic loop");
    }
    w->r = w->x + size;
    w->r_step = w->r + size;
    w->x_trial = w->r_step + size;
    w->dx = w->x_trial + size;
    w->rows = w->analytic + size;
    for (int m = 0; m < g->size; ++m) {
        ssx_component *c = sys->components[sys->order[g->first + m]];
        for (int i = 0; i < c->n_inputs; ++i) {
            int driver = c->input_driver[i];
            if (driver >= 0 && c->input_ports[i].type == SSX_REAL &&
                in_group(sys, g, sys->connections[driver].src_component)) {
                w->owner[w->n] = c;
                w->input[w->n] = i;
                w->x[w->n] = c->inputs[i];
                w->n++;
            }
        }
    }
    for (int k = 0; k < w->n; ++k) {
        w->analytic[k] = has_directional_derivatives(w, w->owner[k]);
    }
    return 0;
}

/* r = x - (scale * output(x) + offset): evaluates every member at zero time with inputs x. */
static int residual(loop_work *w, const double *x, double *r)
{
    ssx_system *sys = w->sys;
    for (int k = 0; k < w->n; ++k) {
        w->owner[k]->inputs[w->input[k]] = x[k];
    }
    for (int m = 0; m < w->group->size; ++m) {
        ssx_component *c = sys->components[sys->order[w->group->first + m]];
        if (component_evaluate_outputs(sys, c, w->t) != 0) {
            return -1;
        }
    }
    for (int k = 0; k < w->n; ++k) {
        const ssx_connection *link = driver_of(w, k);
        double driven = link->scale * sys->components[link->src_component]->outputs[link->src_output] +
                        link->offset;
        r[k] = x[k] - driven;
    }
    return 0;
}

static double norm_inf(const double *v, int n)
{
    double largest = 0.0;
    for (int k = 0; k < n; ++k) {
        double a = fabs(v[k]);
        largest = a > largest || isnan(a) ? a : largest;
    }
    return largest;
}

/* Solves a x = b in place (b becomes x) by Gaussian elimination with partial pivoting. */
static int solve_dense(double *a, double *b, int n)
{
    for (int col = 0; col < n; ++col) {
        int pivot = col;
        for (int row = col + 1; row < n; ++row) {
            if (fabs(a[row * n + col]) > fabs(a[pivot * n + col])) {
                pivot = row;
            }
        }
        if (!(fabs(a[pivot * n + col]) > DBL_EPSILON)) {
            return -1;
        }
        if (pivot != col) {
            for (int k = 0; k < n; ++k) {
                double swap = a[col * n + k];
                a[col * n + k] = a[pivot * n + k];
                a[pivot * n + k] = swap;
            }
            double swap = b[col];
            b[col] = b[pivot];
            b[pivot] = swap;
        }
        for (int row = col + 1; row < n; ++row) {
            double factor = a[row * n + col] / a[col * n + col];
            for (int k = col; k < n; ++k) {
                a[row * n + k] -= factor * a[col * n + k];
            }
            b[row] -= factor * b[col];
        }
    }
    for (int row = n - 1; row >= 0; --row) {
        double sum = b[row];
        for (int k = row + 1; k < n; ++k) {
            sum -= a[row * n + k] * b[k];
        }
        b[row] = sum / a[row * n + row];
    }
    return 0;
}

/* Column j from the owner's fmi2GetDirectionalDerivative at the current point: input j moves
 * only the owner's outputs, so dr_k/dx_j = delta_kj - scale_k d(output driving k)/d(input j). */
static int directional_column(loop_work *w, int j)
{
    ssx_system *sys = w->sys;
    ssx_component *c = w->owner[j];
    int n_rows = 0;
    for (int k = 0; k < w->n; ++k) {
        const ssx_connection *link = driver_of(w, k);
        w->jacobian[k * w->n + j] = k == j ? 1.0 : 0.0;
        if (link->src_component == c->index) {
            w->rows[n_rows] = k;
            w->output_vr[n_rows] = c->output_ports[link->src_output].vr;
            n_rows++;
        }
    }
    if (n_rows == 0) {
        return 0;
    }
    const unsigned int known = c->input_ports[w->input[j]].vr;
    const double seed = 1.0;
    sys->stats.directional_derivatives++;
    if (c->ops->directional_derivative(sys, c, w->output_vr, (size_t)n_rows, &known, 1, &seed,
                                       w->r_step, w->t) != 0) {
        return -1;
    }
    for (int m = 0; m < n_rows; ++m) {
        int k = w->rows[m];
        w->jacobian[k * w->n + j] -= driver_of(w, k)->scale * w->r_step[m];
    }
    return 0;
}

/* The Jacobian at w->x, whose residual w->r was just evaluated (every member is at w->x):
 * directional derivatives first, while the FMUs still hold x, then finite differences. */
static int jacobian(loop_work *w)
{
    int n = w->n;
    for (int j = 0; j < n; ++j) {
        if (w->analytic[j] && directional_column(w, j) != 0) {
            return -1;
        }
    }
    for (int j = 0; j < n; ++j) {
        if (w->analytic[j]) {
            continue;
        }
        memcpy(w->x_trial, w->x, (size_t)n * sizeof *w->x);
        double delta = sqrt(DBL_EPSILON) * fmax(1.0, fabs(w->x[j]));
        w->x_trial[j] += delta;
        if (residual(w, w->x_trial, w->r_step) != 0) {
            return -1;
        }
        for (int k = 0; k < n; ++k) {
            w->jacobian[k * n + j] = (w->r_step[k] - w->r[k]) / delta;
        }
    }
    return 0;
}

/* Returns 1 when converged, 0 when not, -1 on a component failure. */
static int newton(loop_work *w, double *residual_norm)
{
    ssx_system *sys = w->sys;
    int n = w->n;
    for (int iteration = 0; iteration < sys->loop.max_iterations; ++iteration) {
        if (run_interrupted(sys, w->t) != 0 || residual(w, w->x, w->r) != 0) {
            return -1;
        }
        *residual_norm = norm_inf(w->r, n);
        if (*residual_norm <= sys->loop.tolerance) {
            return 1;
        }
        if (!isfinite(*residual_norm)) {
            return 0;
        }
        sys->stats.loop_iterations++;
        if (jacobian(w) != 0) {
            return -1;
        }
        for (int k = 0; k < n; ++k) {
            w->dx[k] = -w->r[k];
        }
        if (solve_dense(w->jacobian, w->dx, n) != 0) {
            return 0;
        }
        for (int k = 0; k < n; ++k) {
            w->x[k] += sys->loop.damping * w->dx[k];
        }
    }
    if (residual(w, w->x, w->r) != 0) {
        return -1;
    }
    *residual_norm = norm_inf(w->r, n);
    return *residual_norm <= sys->loop.tolerance;
}

/* x <- x - damping * r(x), i.e. towards the driven values. */
static int fixed_point(loop_work *w, const double *x_start, double *residual_norm)
{
    ssx_system *sys = w->sys;
    int n = w->n;
    memcpy(w->x, x_start, (size_t)n * sizeof *w->x);
    for (int iteration = 0; iteration < sys->loop.max_iterations; ++iteration) {
        if (run_interrupted(sys, w->t) != 0 || residual(w, w->x, w->r) != 0) {
            return -1;
        }
        *residual_norm = norm_inf(w->r, n);
        if (*residual_norm <= sys->loop.tolerance) {
            return 1;
        }
        if (!isfinite(*residual_norm)) {
            return 0;
        }
        sys->stats.loop_iterations++;
        for (int k = 0; k < n; ++k) {
            w->x[k] -= sys->loop.damping * w->r[k];
        }
    }
    if (residual(w, w->x, w->r) != 0) {
        return -1;
    }
    *residual_norm = norm_inf(w->r, n);
    return *residual_norm <= sys->loop.tolerance;
}

static int report_failure(loop_work *w, double residual_norm)
{
    ssx_system *sys = w->sys;
    char names[1024] = "";
    size_t used = 0;
    for (int m = 0; m < w->group->size && used < sizeof names; ++m) {
        const ssx_component *c = sys->components[sys->order[w->group->first + m]];
        int written = snprintf(names + used, sizeof names - used, "%s'%s'", m ? ", " : "",
                               c->name);
        used += written > 0 ? (size_t)written : 0;
    }
    return fail_kind(
        sys, SSX_ERROR_LOOP, sys->order[w->group->first], -1, w->t,
        "the algebraic loop of components %s did not converge at t=%.17g: residual norm "
        "%.3g after %d Newton and %d fixed-point iterations (tolerance %.3g)",
        names, w->t, residual_norm, sys->loop.max_iterations, sys->loop.max_iterations,
        sys->loop.tolerance);
}

int loop_solve(ssx_system *sys, const ssx_group *group, double t)
{
    loop_work w;
    if (work_init(&w, sys, group, t) != 0) {
        return -1;
    }
    sys->stats.loop_solves++;
    if (w.n == 0) {
        /* no input driven from inside the group: a plain zero-time evaluation settles it */
        int status = residual(&w, w.x, w.r);
        work_free(&w);
        return status;
    }
    double *x_start = malloc((size_t)w.n * sizeof *x_start);
    if (x_start == NULL) {
        work_free(&w);
        return fail(sys, -1, -1, t, "out of memory solving an algebraic loop");
    }
    memcpy(x_start, w.x, (size_t)w.n * sizeof *x_start);
    double residual_norm = INFINITY;
    int outcome = newton(&w, &residual_norm);
    if (outcome == 0) {
        outcome = fixed_point(&w, x_start, &residual_norm);
    }
    if (outcome == 0) {
        report_failure(&w, residual_norm);
        outcome = -1;
    }
    free(x_start);
    work_free(&w);
    return outcome == 1 ? 0 : -1;
}
