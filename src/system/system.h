/* The system's internal layout, shared by the engine's source files. It includes only what
 * needs no system itself; the rooms that read the system (components, the algorithm, the
 * indicators, the recording) are named here by their types alone. */
#ifndef SSX_SYSTEM_H
#define SSX_SYSTEM_H

#include <stdatomic.h>

#include "arena.h"
#include "localization_log.h"
#include "monitor.h"
#include "syssimx_engine.h"
#include "text_table.h"

typedef struct ssx_component ssx_component;
typedef struct ssx_component_ops ssx_component_ops;
typedef struct ssx_master_algorithm ssx_master_algorithm;
typedef struct ssx_indicator ssx_indicator;
typedef struct indicator_state indicator_state;
typedef struct ssx_recording ssx_recording;

typedef struct {
    int src_component;
    int src_output;
    int dst_component;
    int dst_input;
    double scale;
    double offset;
} ssx_connection;

typedef struct {
    int first;  /* offset into the schedule order */
    int size;
    int is_loop;
} ssx_group;

typedef struct {
    double tolerance;
    int max_iterations;
    double damping;
    ssx_loop_jacobian jacobian;
} ssx_loop_options;

typedef struct {
    double tol_time;
    double tol_value;
    int max_iterations;
    int max_microsteps;
    int record_internal_steps;
    ssx_locator locator;
    double zeno_min_interval; /* <= 0: ten times tol_time */
} ssx_hybrid_options;

/* Where the execution stands on its communication grid origin + k*dt (simulation.c): the
 * step under way, left before its end only at an event. */
typedef struct {
    double origin;
    double dt;        /* 0: no step taken since ssx_initialize (the next call's dt is taken) */
    long next;        /* index of the first grid point not reached */
    double step_start; /* the communication step under way: [step_start, step_end] */
    double step_end;
    int in_step;      /* 0: the next step starts at the current time */
} execution_grid;

/* Where the current thread's failures and termination requests go (error.h): while a batch
 * of components steps on several threads, each thread's own (parallel_step.c sets them);
 * without them, the system's. */
typedef struct {
    ssx_error *(*error)(void *owner);
    ssx_termination *(*termination)(void *owner);
    void *owner;
} thread_records;

struct ssx_system {
    char *name;
    ssx_component **components;
    int n_components;
    size_t components_capacity;

    ssx_connection *connections;
    int n_connections;
    size_t connections_capacity;

    ssx_indicator *indicators;
    int n_indicators;
    size_t indicators_capacity;
    /* per indicator, set up by the hybrid algorithm at ssx_initialize */
    indicator_state *indicator_states;

    /* the subscriptions to event sources and the sources' own data (event_source.c); NULL
     * until the first */
    struct event_sources *event_sources;

    int *order;          /* schedule: component indices, group after group */
    double *port_block;  /* every component's port values, in schedule order (port_block.h) */
    size_t port_block_size;
    ssx_group *groups;
    int n_groups;
    int has_schedule;

    ssx_coupling coupling;
    int threads;                    /* ssx_set_threads */
    struct parallel_plan *parallel; /* built at ssx_initialize when threads > 1 */
    int input_order;                /* ssx_set_input_order */
    int extrapolate_held_inputs;    /* ssx_set_extrapolate_held_inputs */
    ssx_step_control step_control;  /* ssx_set_step_control */
    int *power_bonds;               /* ssx_set_power_bonds: 4 ints per bond */
    int n_power_bonds;
    struct input_motion *input_motion;      /* input_order.h, at ssx_initialize */
    struct adaptive_workspace *adaptive;    /* adaptive.h, at ssx_initialize */
    /* chosen at ssx_initialize */
    const ssx_master_algorithm *algorithm;
    void *algorithm_workspace; /* the algorithm's own state (algorithm.h) */
    int (*coupled_step)(ssx_system *sys, double t, double h); /* the coupling's step */
    /* writes c's input derivatives over the coming step after its inputs (input_order.h, set
     * at ssx_initialize; NULL before): the FMU kind calls it and knows no input order */
    int (*write_input_derivatives)(ssx_system *sys, ssx_component *c);
    ssx_loop_options loop;
    ssx_hybrid_options hybrid;

    text_table texts; /* of the String ports (ssx_text_number) */
    ssx_recording *recording;
    int record_hooks_observed; /* a component's record hook was set: its observer is added */
    ssx_localization_log localization;
    ssx_statistics stats;
    ssx_error error;
    ssx_termination termination;
    thread_records thread_records; /* all NULL: failures go to error and termination */
    int allow_non_finite;
    ssx_monitor monitor;

    double time;
    execution_grid grid;
    int initialized;
    int stepping_hybrid; /* FMUs are told that a rollback may follow */
    /* ssx_set_stop_at_own_events asked for; own_event_stops: granted by ssx_initialize (every
     * component can roll back, so a step can be taken again to end at a member's event) */
    int stop_at_own_events;
    int own_event_stops;
    arena component_blocks; /* every component's block (system_add_component) */
    /* what initialize prepares for the members' steps (component_prepare), made again at each
     * initialize: in schedule order and in large pages, beside nothing else */
    arena prepared_blocks;
    /* 0: no component holds an own event (own_events.h), so a commit need not ask each one;
     * set by a report, on a worker thread too */
    atomic_int own_events_pending;
    /* outputs that were NaN or infinite though they feed nothing (finite_outputs.h); counted
     * on a worker thread too */
    atomic_int non_finite_unfed;
    /* per component, the FMU the system loaded itself (ssx_plan_build) and frees with itself;
     * NULL where the FMU is borrowed */
    ssx_fmu **owned_fmus;
    int n_owned_fmus;
};

/* The system's structure changed: it is initialized again before it runs. */
static inline void system_structure_changed(ssx_system *sys)
{
    sys->initialized = 0;
}
static inline int system_is_hybrid(const ssx_system *sys)
{
    return sys->n_indicators > 0;
}

#endif
