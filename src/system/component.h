/* One component of a system: its ports and the behaviour behind one interface, a table of
 * operations per kind (FMU, Model Exchange FMU, Python, table source). Callers go through
 * component_calls.h, where a hook set from Python replaces the matching built-in. */
#ifndef SSX_COMPONENT_H
#define SSX_COMPONENT_H

#include <stddef.h>

#include "syssimx_engine.h"

/* Slot 0 holds the macro-step snapshot, slot 1 the short probe after an event. */
enum { SSX_SNAPSHOT_SLOTS = 2 };

typedef struct ssx_component ssx_component;

/* An event the component handled inside its own step (own_events.h). */
typedef struct {
    double t;
    ssx_own_event_kind kind;
    int clock; /* ssx_event_record's clock: 1 + index, 0 none */
    /* reported at the end of the step that held it: its FMU cannot return early */
    int at_step_end;
} ssx_own_event;

typedef struct {
    ssx_own_event *pending; /* in time order */
    size_t n;
    size_t capacity;
} ssx_own_event_list;

/* What a component can do beyond stepping, for the algorithms that use it. */
typedef struct {
    int directional_derivatives; /* providesDirectionalDerivative(s) */
    int can_interpolate_inputs;  /* canInterpolateInputs: takes its inputs' time derivatives */
    int max_output_derivative_order; /* maxOutputDerivativeOrder: tells its outputs' */
} ssx_component_capabilities;

struct byte_writer; /* support/byte_stream.h */
struct byte_reader;

/* A component's state held by its caller (a whole-system state, run/saved_state.c), apart
 * from its port values, which the engine saves itself. Unlike the snapshot slots, each save
 * makes a new state. */
typedef struct component_state_ops {
    /* The state as it stands: a new one, or NULL with the error set. */
    void *(*save)(ssx_system *sys, ssx_component *c);
    /* Back to `state`, now at time t: 0, or -1 with the error set. */
    int (*restore)(ssx_system *sys, ssx_component *c, const void *state, double t);
    /* Frees the state (it remembers what it needs for that). */
    void (*free)(void *state);
    /* Appends the state's bytes: 0, or -1 with the error set. */
    int (*serialize)(ssx_system *sys, ssx_component *c, const void *state,
                     struct byte_writer *out);
    /* A state of c from bytes that serialize wrote: NULL with the error set. */
    void *(*deserialize)(ssx_system *sys, ssx_component *c, struct byte_reader *in);
} component_state_ops;

typedef struct ssx_component_ops {
    int (*do_step)(ssx_system *sys, ssx_component *c, double t, double dt);
    int (*write_inputs)(ssx_system *sys, ssx_component *c);
    int (*read_outputs)(ssx_system *sys, ssx_component *c);
    int (*evaluate_outputs)(ssx_system *sys, ssx_component *c, double t);
    int (*snapshot)(ssx_system *sys, ssx_component *c, int slot);
    int (*restore)(ssx_system *sys, ssx_component *c, int slot, double t);
    /* frees what c->data holds, and c->data unless it lies in the component's block
     * (system_add_component); NULL when the kind keeps none */
    void (*release)(ssx_component *c);
    /* What callers would otherwise ask the kind for. Each may be NULL: the kind has none. */
    /* Refuses a component the run cannot use (a Python component without its two hooks). */
    int (*validate)(ssx_system *sys, const ssx_component *c);
    /* After initialization: unconnected inputs whose start is NaN take the value the
     * component holds (an FMU's own start). NULL: every start is given. */
    int (*adopt_inputs)(ssx_system *sys, ssx_component *c, double t0);
    /* The system's initialization of a component left in initialization mode (an FMU started
     * by ssx_fmu_enter_initialization). Both write its driven inputs there; initial_outputs
     * then reads its outputs where its standard allows, leave_initialization makes it leave.
     * Once it left, both do nothing. NULL: the kind has no such mode. */
    int (*initial_outputs)(ssx_system *sys, ssx_component *c, double t0);
    int (*leave_initialization)(ssx_system *sys, ssx_component *c, double t0);
    /* d outputs / d inputs (value references) in the direction seed, into out, as the
     * component stands at t; fails with the error set. NULL: the kind cannot tell. */
    int (*directional_derivative)(ssx_system *sys, ssx_component *c, const unsigned int *outputs,
                                  size_t n_outputs, const unsigned int *inputs, size_t n_inputs,
                                  const double *seed, double *out, double t);
    /* What two components must never use on two threads at once (their FMU instance), NULL:
     * nothing shared. Only kinds whose built-in step may run on a worker thread have it. */
    const void *(*shared_with_threads)(const ssx_component *c);
    /* At initialization, after the ports are final: what the kind builds from them, in the
     * system's prepared blocks (system.h); -1: out of memory. */
    int (*prepare)(ssx_system *sys, ssx_component *c);
    /* Forgets what prepare built, before the system gives those blocks back. */
    void (*unprepare)(ssx_component *c);
    /* Whether the component can save and restore its state (with its hooks as set). */
    int (*can_roll_back)(const ssx_component *c);
    /* What it can do (directional derivatives, moving inputs). NULL: nothing. */
    ssx_component_capabilities (*capabilities)(const ssx_component *c);
    /* The first time derivative of each Real output at t into slope[output] (other entries
     * untouched); 0, or -1 with the error set. Only kinds with max_output_derivative_order. */
    int (*output_derivatives)(ssx_system *sys, ssx_component *c, double t, double *slope);
    /* Hands the component the first `order` time derivatives of its Real inputs over the
     * coming step, derivatives[2 * input + k - 1] the k-th of input `input`. Only kinds that
     * can interpolate inputs. 1: the component refused this order (nothing set, no error). */
    int (*set_input_derivatives)(ssx_system *sys, ssx_component *c, int order,
                                 const double *derivatives);
    /* The kind's own reaction to an event at t when no Python hook handles it (an FMU's
     * declarative restart). NULL: none. */
    int (*handle_events)(ssx_system *sys, ssx_component *c, double t);
    /* FMI 3.0: its triggered input clock `clock` (an index among its FMU's triggered clocks)
     * ticks at t, where it stands (ssx_connect_clock). NULL: it has none. */
    int (*tick_triggered_clock)(ssx_system *sys, ssx_component *c, int clock, double t);
    /* The FMU it runs (a run watches an isolated FMU's host). NULL: it runs none. */
    ssx_fmu *(*fmu)(const ssx_component *c);
    /* Its state saved by handle (component_state_ops). NULL: it cannot be (a Python component). */
    const component_state_ops *saved_state;
    /* The kind's reads check its outputs for NaN and infinities; a Python hook that steps
     * it calls them. 0: values Python wrote are checked after the hook. */
    int checks_own_outputs;
} ssx_component_ops;

/* A driven input, resolved for the coupling loop: inputs[input] = scale * *source + offset,
 * source pointing at the driving output (valid from one initialization to the next). */
typedef struct {
    int input;
    const double *source;
    double scale;
    double offset;
} ssx_input_link;

typedef struct {
    ssx_value_type type;
    unsigned int vr;
} ssx_port;

/* What the engine knows of an output's values (finite_outputs.h), set at each initialize. */
typedef struct {
    int feeds;               /* a connection or an event indicator reads it */
    double first_non_finite; /* the first time it was NaN or infinite, NaN: never */
} ssx_output_watch;

struct ssx_component {
    /* what every step reads, together at the start */
    const ssx_component_ops *ops;
    void *data; /* the kind's own data (a table source's table, an FMU's), ops->release frees */
    double *inputs;  /* in the system's port block once initialized (ports_in_block) */
    double *outputs;
    ssx_input_link *links; /* the driven inputs, built with the schedule (coupling.c) */
    int n_links;
    int n_inputs;
    int n_outputs;
    int ports_in_block; /* inputs and outputs lie in the system's port block (port_block.h) */
    int has_step_hook;  /* hooks.do_step is set: told in the line every step reads */
    ssx_hooks hooks;

    char *name;
    int index;
    int can_snapshot;
    int calling_thread_only; /* ssx_set_calling_thread_only */
    ssx_port *output_ports;
    ssx_port *input_ports;
    double *input_starts;
    int *input_driver; /* connection index driving each input, or -1 */

    /* engine-side port values saved with each snapshot, so a restore brings them back too */
    double *saved_outputs[SSX_SNAPSHOT_SLOTS];
    double *saved_inputs[SSX_SNAPSHOT_SLOTS];
    /* events handled inside its steps, until the master accepts them (own_events.h) */
    ssx_own_event_list own_events;
    /* one per output, from ssx_initialize on (NULL before) */
    ssx_output_watch *output_watch;
};

/* The state of a kind that holds none beyond its ports (a table source): every member NULL. */
extern const component_state_ops component_no_saved_state;
extern const ssx_component_ops ssx_fmu_component_ops;
/* A Model Exchange FMU integrated by the engine (me_component.c); its ports are an FMU
 * component's. */
extern const ssx_component_ops ssx_model_exchange_component_ops;
extern const ssx_component_ops ssx_python_component_ops;
extern const ssx_component_ops ssx_table_component_ops;

#endif
