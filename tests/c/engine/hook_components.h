/* Components whose steps are C hooks, as Python components are to the engine: a counter, a
 * sampler, and how to add one with one output and, if asked, one input. */
#ifndef SSX_TEST_HOOK_COMPONENTS_H
#define SSX_TEST_HOOK_COMPONENTS_H

#include "syssimx_engine.h"

typedef struct {
    ssx_system *sys;
    int component;
} hook_component;

typedef int (*hook_step)(void *user, double t, double dt);

/* counter: its output counts the steps taken */
int hook_count(void *user, double t, double dt);

/* sampler: its output is the input it saw when it stepped */
int hook_sample(void *user, double t, double dt);

/* Adds `name` stepped by `do_step`, with one Real output and, where with_input, one Real input
 * starting at 0; `b` must outlive the system. Returns the component's index. */
int hook_add(ssx_system *sys, const char *name, hook_component *b, hook_step do_step,
             int with_input);

#endif
