/* The components' public built-ins: what a Python override reaches as super(). Never a hook,
 * never counted. */
#include "component.h"
#include "error.h"
#include "system.h"

int ssx_component_do_step(ssx_system *sys, int component, double t, double dt)
{
    ssx_component *c = system_component(sys, component);
    return c == NULL ? -1 : c->ops->do_step(sys, c, t, dt);
}

int ssx_component_write_inputs(ssx_system *sys, int component)
{
    ssx_component *c = system_component(sys, component);
    return c == NULL ? -1 : c->ops->write_inputs(sys, c);
}

int ssx_component_read_outputs(ssx_system *sys, int component)
{
    ssx_component *c = system_component(sys, component);
    return c == NULL ? -1 : c->ops->read_outputs(sys, c);
}

int ssx_component_snapshot(ssx_system *sys, int component, int slot)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (slot < 0 || slot >= SSX_SNAPSHOT_SLOTS) {
        return fail(sys, component, -1, sys->time, "component '%s': snapshot slot %d out of range",
                    c->name, slot);
    }
    return c->ops->snapshot(sys, c, slot);
}

int ssx_component_restore(ssx_system *sys, int component, int slot, double t)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (slot < 0 || slot >= SSX_SNAPSHOT_SLOTS) {
        return fail(sys, component, -1, t, "component '%s': snapshot slot %d out of range",
                    c->name, slot);
    }
    return c->ops->restore(sys, c, slot, t);
}
