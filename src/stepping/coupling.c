/* Jacobi and Gauss-Seidel macro steps over the schedule, on one thread or several
 * (parallel_step.h). */
#include "coupling.h"

#include <math.h>
#include <stdlib.h>

#include "algebraic_loop.h"
#include "component_calls.h"
#include "error.h"
#include "input_links.h"
#include "input_order.h"
#include "parallel_step.h"
#include "port_block.h"

typedef int (*coupled_step)(ssx_system *sys, double t, double h);

static int step_gauss_seidel(ssx_system *sys, double t, double h);
static int step_gauss_seidel_batches(ssx_system *sys, double t, double h);
static int step_jacobi(ssx_system *sys, double t, double h);

/* The couplings' steps on one thread and on several, chosen once per initialization. Jacobi
 * is one batch either way. */
static const coupled_step COUPLED_STEPS[][2] = {
    [SSX_GAUSS_SEIDEL] = {step_gauss_seidel, step_gauss_seidel_batches},
    [SSX_JACOBI] = {step_jacobi, step_jacobi},
};

int coupling_known(int coupling)
{
    return coupling >= 0 && coupling < (int)(sizeof COUPLED_STEPS / sizeof *COUPLED_STEPS);
}

static int prepare_schedule(ssx_system *sys);

static int prepare_members(ssx_system *sys);

static int prepare_links(ssx_system *sys);

int coupling_prepare(ssx_system *sys)
{
    if (prepare_schedule(sys) != 0 || prepare_members(sys) != 0 || port_block_lay_out(sys) != 0 ||
        prepare_links(sys) != 0 || parallel_prepare(sys) != 0) {
        return -1;
    }
    sys->coupled_step = COUPLED_STEPS[sys->coupling][sys->parallel != NULL];
    return 0;
}

static int prepare_schedule(ssx_system *sys)
{
    if (sys->has_schedule) {
        const ssx_group *last = &sys->groups[sys->n_groups - 1];
        if (last->first + last->size != sys->n_components) {
            return fail(sys, -1, -1, sys->time,
                        "system '%s': the schedule lists %d components but the system now has "
                        "%d; set the schedule again after adding components",
                        sys->name, last->first + last->size, sys->n_components);
        }
        return 0;
    }
    int n = sys->n_components;
    int *order = malloc(((size_t)n + 1) * sizeof *order);
    ssx_group *groups = malloc(((size_t)n + 1) * sizeof *groups);
    if (order == NULL || groups == NULL) {
        free(order);
        free(groups);
        return fail(sys, -1, -1, sys->time, "out of memory building the default schedule");
    }
    for (int i = 0; i < n; ++i) {
        order[i] = i;
        groups[i] = (ssx_group){.first = i, .size = 1, .is_loop = 0};
    }
    free(sys->order);
    free(sys->groups);
    sys->order = order;
    sys->groups = groups;
    sys->n_groups = n;
    return 0;
}

/* In schedule order: what each member's step reads then lies in the order of the steps, one
 * member's after the other's, and the snapshot copies (read only by rollbacks) after them all.
 * Made afresh at each initialize, in blocks sized for all of it. */
static int prepare_members(ssx_system *sys)
{
    size_t bytes = 0;
    for (int i = 0; i < sys->n_components; ++i) {
        component_unprepare(sys->components[i]);
        bytes += component_prepared_bytes(sys->components[i]);
    }
    arena_free(&sys->prepared_blocks);
    arena_expect(&sys->prepared_blocks, bytes);
    for (int k = 0; k < sys->n_components; ++k) {
        ssx_component *c = sys->components[sys->order[k]];
        if (component_prepare(sys, c) != 0) {
            return fail(sys, c->index, -1, sys->time, "out of memory preparing component '%s'",
                        c->name);
        }
    }
    for (int k = 0; k < sys->n_components; ++k) {
        ssx_component *c = sys->components[sys->order[k]];
        if (component_prepare_snapshots(sys, c) != 0) {
            return fail(sys, c->index, -1, sys->time, "out of memory preparing component '%s'",
                        c->name);
        }
    }
    return 0;
}

/* Each component's driven inputs as one array of links straight to the driving outputs (in
 * the port block: after the output just written): the coupling loop reads no connection table
 * and skips the undriven inputs. The room for them was made by component_prepare. */
static int prepare_links(ssx_system *sys)
{
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        c->n_links = 0;
        for (int k = 0; k < c->n_inputs; ++k) {
            int driver = c->input_driver[k];
            if (driver >= 0) {
                const ssx_connection *link = &sys->connections[driver];
                c->links[c->n_links++] = (ssx_input_link){
                    .input = k,
                    .source = &sys->components[link->src_component]->outputs[link->src_output],
                    .scale = link->scale,
                    .offset = link->offset};
            }
        }
    }
    return 0;
}

void coupling_propagate_inputs(ssx_system *sys, ssx_component *c)
{
    input_links_apply(c);
    input_order_propagate(sys, c);
}

static ssx_component *member(ssx_system *sys, const ssx_group *g, int m)
{
    return sys->components[sys->order[g->first + m]];
}

int coupling_step_member(ssx_system *sys, ssx_component *c, double t, double h)
{
    if (component_write_inputs(sys, c) != 0) {
        return -1;
    }
    return component_do_step(sys, c, t, h);
}

/* A loop group is solved at the end of its step, at t + h: the sample recorded there satisfies
 * the loop equations, and its solved inputs are the consistent start of the next step (kept with
 * the snapshots, so a restore brings them back too). */
static int solve_loop_at(ssx_system *sys, const ssx_group *g, double t)
{
    input_order_measure_loop(sys, g);
    for (int m = 0; m < g->size; ++m) {
        coupling_propagate_inputs(sys, member(sys, g, m));
    }
    return loop_solve(sys, g, t);
}

/* Gauss-Seidel: each component's inputs come from the latest outputs, just before it steps.
 * Loop members step from the loop's solution at t instead. */
static int step_gauss_seidel(ssx_system *sys, double t, double h)
{
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        const ssx_group *g = &sys->groups[gi];
        for (int m = 0; m < g->size; ++m) {
            ssx_component *c = member(sys, g, m);
            if (!g->is_loop) {
                coupling_propagate_inputs(sys, c);
            }
            if (coupling_step_member(sys, c, t, h) != 0) {
                return -1;
            }
        }
        if (g->is_loop && solve_loop_at(sys, g, t + h) != 0) {
            return -1;
        }
    }
    return 0;
}

/* Gauss-Seidel on several threads: the members of a batch see the same driver outputs when
 * all their inputs are set before any of them steps (parallel_step.h). */
static int step_gauss_seidel_batches(ssx_system *sys, double t, double h)
{
    const parallel_batch *batches;
    int n_batches = parallel_batches(sys->parallel, &batches);
    for (int b = 0; b < n_batches; ++b) {
        const int *members = &sys->order[batches[b].first];
        for (int m = 0; m < batches[b].size && batches[b].group < 0; ++m) {
            coupling_propagate_inputs(sys, sys->components[members[m]]);
        }
        if (parallel_step(sys, members, batches[b].size, t, h, coupling_step_member) != 0) {
            return -1;
        }
        if (batches[b].group >= 0 &&
            solve_loop_at(sys, &sys->groups[batches[b].group], t + h) != 0) {
            return -1;
        }
    }
    return 0;
}

/* Jacobi: every input comes from the outputs at t; then all components step, and the loops are
 * solved with every output at t + h. */
static int step_jacobi(ssx_system *sys, double t, double h)
{
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        const ssx_group *g = &sys->groups[gi];
        for (int m = 0; m < g->size && !g->is_loop; ++m) {
            coupling_propagate_inputs(sys, member(sys, g, m));
        }
    }
    if (parallel_step(sys, sys->order, sys->n_components, t, h, coupling_step_member) != 0) {
        return -1;
    }
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        const ssx_group *g = &sys->groups[gi];
        if (g->is_loop && solve_loop_at(sys, g, t + h) != 0) {
            return -1;
        }
    }
    return 0;
}

/* One Gauss-Seidel sweep over a loop's members at t0: each one's driven inputs from the latest
 * outputs, then its outputs (in initialization mode where it still is). Returns how far the
 * inputs moved (NaN when one became NaN), or -1 on a failure. */
static double initial_sweep(ssx_system *sys, const ssx_group *g, double t0)
{
    double moved = 0.0;
    for (int m = 0; m < g->size; ++m) {
        ssx_component *c = member(sys, g, m);
        for (int i = 0; i < c->n_links; ++i) {
            const ssx_input_link *link = &c->links[i];
            double value = link->scale * *link->source + link->offset;
            double change = fabs(value - c->inputs[link->input]);
            moved = isnan(change) || change > moved ? change : moved;
            c->inputs[link->input] = value;
        }
        if (component_initial_outputs(sys, c, t0) != 0) {
            return -1.0;
        }
    }
    return moved;
}

/* A loop's members, before they leave initialization mode, are swept until no input moves by
 * more than the loop tolerance. Sweeps that stop contracting end early: the loop is solved once
 * they left, as at any instant, and decides then. */
static int iterate_initial_loop(ssx_system *sys, const ssx_group *g, double t0)
{
    double previous = INFINITY;
    for (int sweep = 0; sweep < sys->loop.max_iterations; ++sweep) {
        double moved = initial_sweep(sys, g, t0);
        if (moved < 0.0) {
            return -1;
        }
        if (moved <= sys->loop.tolerance || !(moved < previous)) {
            return 0;
        }
        previous = moved;
    }
    return 0;
}

/* A group's outputs at t consistent with its inputs from the outputs as they are. */
static int settle_group(ssx_system *sys, const ssx_group *g, double t)
{
    for (int m = 0; m < g->size; ++m) {
        ssx_component *c = member(sys, g, m);
        coupling_propagate_inputs(sys, c);
        if (!g->is_loop && component_evaluate_outputs(sys, c, t) != 0) {
            return -1;
        }
    }
    return g->is_loop ? loop_solve(sys, g, t) : 0;
}

/* A group's members leave initialization mode with their driven inputs at t0: a loop is
 * iterated there first; then each member's inputs are set and it starts, its outputs are
 * evaluated, and a loop is solved as at any instant. */
static int start_group(ssx_system *sys, const ssx_group *g, double t0)
{
    if (g->is_loop && iterate_initial_loop(sys, g, t0) != 0) {
        return -1;
    }
    for (int m = 0; m < g->size; ++m) {
        ssx_component *c = member(sys, g, m);
        coupling_propagate_inputs(sys, c);
        if (component_start(sys, c, t0) != 0 ||
            (!g->is_loop && component_evaluate_outputs(sys, c, t0) != 0)) {
            return -1;
        }
    }
    return g->is_loop ? loop_solve(sys, g, t0) : 0;
}

/* The order in which the groups start: every driver before the groups it drives (an input's
 * value at t0 is its driver's output once the driver left initialization mode: a 20-sim FMU
 * computes its outputs as it leaves), whatever the schedule, which steps the consumer of a
 * delayed output before its producer. Groups that drive one another through delayed outputs
 * (a strongly connected set of the connections, Tarjan's algorithm) start in schedule order,
 * which follows the outputs that depend on inputs at once. */
typedef struct {
    const ssx_system *sys;
    int *group_of; /* each component's group */
    int *number;   /* each group's visit number, -1 before its visit */
    int *low;      /* the lowest visit number it reaches */
    int *on_stack;
    int *stack;
    int depth;
    int visits;
    int *order; /* the start order, filled from the front */
    int ordered;
    int *drives_itself; /* each group's: a member's output drives a member, with a delay */
    /* where each strongly connected set starts in order, and whether it drives itself (its
     * first groups started from outputs of later ones) */
    int *set_first;
    int *set_cyclic;
    int n_sets;
} start_order;

static int compare_groups(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

static void visit(start_order *o, int gi)
{
    o->number[gi] = o->low[gi] = o->visits++;
    o->stack[o->depth++] = gi;
    o->on_stack[gi] = 1;
    const ssx_group *g = &o->sys->groups[gi];
    for (int m = 0; m < g->size; ++m) {
        const ssx_component *c = o->sys->components[o->sys->order[g->first + m]];
        for (int k = 0; k < c->n_inputs; ++k) {
            if (c->input_driver[k] < 0) {
                continue;
            }
            int driver = o->group_of[o->sys->connections[c->input_driver[k]].src_component];
            o->drives_itself[gi] |= driver == gi && !g->is_loop;
            if (o->number[driver] < 0) {
                visit(o, driver);
                o->low[gi] = o->low[driver] < o->low[gi] ? o->low[driver] : o->low[gi];
            } else if (o->on_stack[driver] && o->number[driver] < o->low[gi]) {
                o->low[gi] = o->number[driver];
            }
        }
    }
    if (o->low[gi] != o->number[gi]) {
        return;
    }
    /* gi roots a strongly connected set, all of whose drivers are ordered already */
    int first = o->ordered;
    int member_group;
    do {
        member_group = o->stack[--o->depth];
        o->on_stack[member_group] = 0;
        o->order[o->ordered++] = member_group;
    } while (member_group != gi);
    qsort(&o->order[first], (size_t)(o->ordered - first), sizeof *o->order, compare_groups);
    o->set_first[o->n_sets] = first;
    o->set_cyclic[o->n_sets++] = o->ordered - first > 1 || o->drives_itself[gi];
}

/* Starts the groups of one strongly connected set, in order. In a set that drives itself the
 * first groups started from outputs the later ones changed as they left initialization mode:
 * the set is settled again, as at any instant. */
static int start_set(ssx_system *sys, const int *groups, int n, int cyclic, double t0)
{
    for (int i = 0; i < n; ++i) {
        if (start_group(sys, &sys->groups[groups[i]], t0) != 0) {
            return -1;
        }
    }
    for (int i = 0; i < n && cyclic; ++i) {
        if (settle_group(sys, &sys->groups[groups[i]], t0) != 0) {
            return -1;
        }
    }
    return 0;
}

int coupling_initialize(ssx_system *sys, double t0)
{
    input_order_forget(sys);
    size_t n = (size_t)sys->n_groups;
    int *arrays = malloc(((size_t)sys->n_components + 9 * n + 1) * sizeof *arrays);
    if (arrays == NULL) {
        return fail(sys, -1, -1, t0, "out of memory initializing system '%s'", sys->name);
    }
    start_order o = {.sys = sys, .group_of = arrays};
    o.number = o.group_of + sys->n_components;
    o.low = o.number + n;
    o.on_stack = o.low + n;
    o.stack = o.on_stack + n;
    o.order = o.stack + n;
    o.drives_itself = o.order + n;
    o.set_first = o.drives_itself + n;
    o.set_cyclic = o.set_first + n;
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        o.number[gi] = -1;
        o.on_stack[gi] = 0;
        o.drives_itself[gi] = 0;
        for (int m = 0; m < sys->groups[gi].size; ++m) {
            o.group_of[sys->order[sys->groups[gi].first + m]] = gi;
        }
    }
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        if (o.number[gi] < 0) {
            visit(&o, gi);
        }
    }
    int status = 0;
    for (int set = 0; set < o.n_sets && status == 0; ++set) {
        int end = set + 1 < o.n_sets ? o.set_first[set + 1] : o.ordered;
        status = start_set(sys, &o.order[o.set_first[set]], end - o.set_first[set],
                           o.set_cyclic[set], t0);
    }
    free(arrays);
    return status;
}

int coupling_settle(ssx_system *sys, double t)
{
    input_order_forget(sys); /* the outputs may jump here */
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        if (settle_group(sys, &sys->groups[gi], t) != 0) {
            return -1;
        }
    }
    return 0;
}
