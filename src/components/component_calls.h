/* Calling a component: a Python hook if set, else its kind's built-in; preparing and freeing
 * it. */
#ifndef SSX_COMPONENT_CALLS_H
#define SSX_COMPONENT_CALLS_H

#include "component.h"
#include "finite_outputs.h"

/* A Python hook if set, else the built-in. Each returns 0 or -1 with the error set. */
int component_do_step(ssx_system *sys, ssx_component *c, double t, double dt);
int component_write_inputs(ssx_system *sys, ssx_component *c);
int component_read_outputs(ssx_system *sys, ssx_component *c);
int component_evaluate_outputs(ssx_system *sys, ssx_component *c, double t);
int component_snapshot(ssx_system *sys, ssx_component *c, int slot);
int component_restore(ssx_system *sys, ssx_component *c, int slot, double t);
/* The event sources in sources[] (ssx_subscribe's numbering) fired at t_event; the system
 * stands at t (the same, except for own events committed at a later communication point): a
 * hook receives t_event, a built-in reaction runs at t. */
int component_handle_events(ssx_system *sys, ssx_component *c, const int *sources, int n,
                            double t_event, double t);
int component_initialize(ssx_system *sys, ssx_component *c, double t0);
/* At ssx_initialize, its driven inputs set: its outputs at t0 while it may still be in
 * initialization mode (a hook evaluates them, else the kind's initial_outputs, else
 * evaluate_outputs). */
int component_initial_outputs(ssx_system *sys, ssx_component *c, double t0);
/* At ssx_initialize, its driven inputs set: it leaves initialization mode with them (when its
 * kind has one), its initialize hook runs and its unset inputs adopt the values it holds. */
int component_start(ssx_system *sys, ssx_component *c, double t0);
int component_record(ssx_system *sys, ssx_component *c, double t);
int component_can_roll_back(const ssx_component *c);

/* Its links' room (filled by the coupling) and what the kind builds from its ports, in the
 * system's prepared blocks; called when the system initializes, member after member in
 * schedule order, so that what each step reads lies in that order. */
int component_prepare(ssx_system *sys, ssx_component *c);
/* The snapshot copies of its ports, in the prepared blocks after every member's step data
 * (read only by rollbacks). */
int component_prepare_snapshots(ssx_system *sys, ssx_component *c);
/* Forgets what the two above made: the system gives those blocks back next. */
void component_unprepare(ssx_component *c);
/* About how many bytes the two above take, for sizing the blocks in advance. */
size_t component_prepared_bytes(const ssx_component *c);
/* Frees what the component holds; its block goes with the system's arena. */
void component_free(ssx_component *c);

#endif
