#include "hook_components.h"

#include "test_support.h"

int hook_count(void *user, double t, double dt)
{
    (void)t;
    (void)dt;
    hook_component *b = user;
    ssx_outputs(b->sys, b->component)[0] += 1.0;
    return 0;
}

int hook_sample(void *user, double t, double dt)
{
    (void)t;
    (void)dt;
    hook_component *b = user;
    ssx_outputs(b->sys, b->component)[0] = ssx_inputs(b->sys, b->component)[0];
    return 0;
}

/* the outputs are what the last step left */
static int keep_outputs(void *user, double t)
{
    (void)user;
    (void)t;
    return 0;
}

int hook_add(ssx_system *sys, const char *name, hook_component *b, hook_step do_step,
             int with_input)
{
    int c = ssx_add_python_component(sys, name, 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, 0) == 0);
    if (with_input) {
        CHECK(ssx_add_input(sys, c, SSX_REAL, 0, 0.0) == 0);
    }
    *b = (hook_component){.sys = sys, .component = c};
    ssx_hooks hooks = {.user = b, .do_step = do_step, .evaluate_outputs = keep_outputs};
    CHECK_OK(sys, ssx_set_hooks(sys, c, &hooks));
    return c;
}
