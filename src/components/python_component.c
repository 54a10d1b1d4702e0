/* Built-in behaviour of a Python component: everything lives in its hooks, and its ports are
 * read and written by Python directly through ssx_inputs()/ssx_outputs(). */
#include "component.h"
#include "error.h"
#include "system.h"

static int python_do_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    if (c->hooks.do_step == NULL) {
        return fail(sys, c->index, -1, t, "component '%s': a Python component needs a do_step hook",
                    c->name);
    }
    return c->hooks.do_step(c->hooks.user, t, dt) == 0 ? 0 : fail_hook(sys, c, t, "do_step");
}

static int python_ports_in_place(ssx_system *sys, ssx_component *c)
{
    (void)sys;
    (void)c;
    return 0; /* the port arrays are the component's own memory: nothing to transfer */
}

static int python_evaluate_outputs(ssx_system *sys, ssx_component *c, double t)
{
    if (c->hooks.evaluate_outputs == NULL) {
        return fail(sys, c->index, -1, t,
                    "component '%s': a Python component needs an evaluate_outputs hook", c->name);
    }
    return c->hooks.evaluate_outputs(c->hooks.user, t) == 0
               ? 0
               : fail_hook(sys, c, t, "evaluate_outputs");
}

static int python_snapshot(ssx_system *sys, ssx_component *c, int slot)
{
    if (c->hooks.snapshot == NULL || !c->can_snapshot) {
        return fail(sys, c->index, -1, sys->time,
                    "component '%s' cannot save its state (no snapshot hook)", c->name);
    }
    return c->hooks.snapshot(c->hooks.user, slot) == 0 ? 0
                                                        : fail_hook(sys, c, sys->time, "snapshot");
}

static int python_restore(ssx_system *sys, ssx_component *c, int slot, double t)
{
    if (c->hooks.restore == NULL || !c->can_snapshot) {
        return fail(sys, c->index, -1, t,
                    "component '%s' cannot restore its state (no restore hook)", c->name);
    }
    return c->hooks.restore(c->hooks.user, slot, t) == 0 ? 0 : fail_hook(sys, c, t, "restore");
}

static int python_can_roll_back(const ssx_component *c)
{
    return c->can_snapshot && c->hooks.snapshot != NULL && c->hooks.restore != NULL;
}

static int python_validate(ssx_system *sys, const ssx_component *c)
{
    if (c->hooks.do_step == NULL || c->hooks.evaluate_outputs == NULL) {
        return fail(sys, c->index, -1, sys->time,
                    "Python component '%s' needs do_step and evaluate_outputs hooks", c->name);
    }
    return 0;
}

const ssx_component_ops ssx_python_component_ops = {
    .do_step = python_do_step,
    .write_inputs = python_ports_in_place,
    .read_outputs = python_ports_in_place,
    .evaluate_outputs = python_evaluate_outputs,
    .snapshot = python_snapshot,
    .restore = python_restore,
    .validate = python_validate,
    .can_roll_back = python_can_roll_back,
};
