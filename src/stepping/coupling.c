/* Jacobi and Gauss-Seidel macro steps over the schedule, on one thread or several
 * (parallel_step.h). */
#include "coupling.h"

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

int coupling_settle(ssx_system *sys, double t)
{
    input_order_forget(sys); /* the outputs may jump here */
    for (int gi = 0; gi < sys->n_groups; ++gi) {
        const ssx_group *g = &sys->groups[gi];
        for (int m = 0; m < g->size; ++m) {
            ssx_component *c = member(sys, g, m);
            coupling_propagate_inputs(sys, c);
            if (!g->is_loop && component_evaluate_outputs(sys, c, t) != 0) {
                return -1;
            }
        }
        if (g->is_loop && loop_solve(sys, g, t) != 0) {
            return -1;
        }
    }
    return 0;
}
