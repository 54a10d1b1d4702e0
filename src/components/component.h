/* One component of a system: its ports and the behaviour behind one interface. Built-in
 * behaviour comes from a table per kind (FMU or Python); a hook set from Python replaces the
 * matching built-in. */
#ifndef SSX_COMPONENT_H
#define SSX_COMPONENT_H

#include "own_events.h"
#include "syssimx_engine.h"

/* Slot 0 holds the macro-step snapshot, slot 1 the short probe after an event. */
enum { SSX_SNAPSHOT_SLOTS = 2 };

typedef struct ssx_component ssx_component;

typedef struct {
    int (*do_step)(ssx_system *sys, ssx_component *c, double t, double dt);
    int (*write_inputs)(ssx_system *sys, ssx_component *c);
    int (*read_outputs)(ssx_system *sys, ssx_component *c);
    int (*evaluate_outputs)(ssx_system *sys, ssx_component *c, double t);
    int (*snapshot)(ssx_system *sys, ssx_component *c, int slot);
    int (*restore)(ssx_system *sys, ssx_component *c, int slot, double t);
    void (*release)(ssx_component *c); /* frees c->data; NULL when the kind keeps none */
} ssx_component_ops;

/* A driven input, resolved for the coupling loop: inputs[input] = scale * *source + offset,
 * source pointing at the driving output (valid from one initialization to the next). */
typedef struct {
    int input;
    const double *source;
    double scale;
    double offset;
} ssx_input_link;

/* Ports of one value type, batched for a single fmi2Get/Set call. */
typedef struct {
    unsigned int *vr;
    int *port; /* index of each entry in the component's port array */
    size_t n;
} ssx_port_batch;

typedef struct {
    ssx_value_type type;
    unsigned int vr;
} ssx_port;

struct ssx_component {
    char *name;
    int index;
    const ssx_component_ops *ops;
    ssx_hooks hooks;
    ssx_fmu *fmu; /* borrowed; NULL for a Python component */
    void *data;   /* the kind's own data (a table source's table), freed by ops->release */
    int can_snapshot;
    int provides_directional_derivatives; /* FMU components only */
    /* FMU components: the modelDescription's canInterpolateInputs and maxOutputDerivativeOrder,
     * and (input_order.h) per input its first and second time derivative over the coming
     * step, NULL while inputs are held */
    int can_interpolate_inputs;
    int max_output_derivative_order;
    double *input_derivatives;
    int calling_thread_only; /* ssx_set_calling_thread_only */

    ssx_port *output_ports;
    double *outputs;
    int n_outputs;
    ssx_port *input_ports;
    double *inputs;
    double *input_starts;
    int *input_driver; /* connection index driving each input, or -1 */
    int n_inputs;
    ssx_input_link *links; /* the driven inputs, built with the schedule (coupling.c) */
    int n_links;

    ssx_port_batch output_batch[3]; /* by ssx_value_type, built at initialization */
    ssx_port_batch input_batch[3];
    double *real_scratch;
    int *int_scratch;
    /* the inputs as last written to the FMU and its values epoch right after that write
     * (-1: nothing written yet); equal inputs at an unchanged epoch need no fmi2Set */
    double *inputs_written;
    long inputs_written_epoch;

    /* built-in FMU snapshots: one reused FMU state per slot, valid for one instance generation */
    void *fmu_state[SSX_SNAPSHOT_SLOTS];
    long fmu_state_generation[SSX_SNAPSHOT_SLOTS];
    /* engine-side port values saved with each snapshot, so a restore brings them back too */
    double *saved_outputs[SSX_SNAPSHOT_SLOTS];
    double *saved_inputs[SSX_SNAPSHOT_SLOTS];
    /* events handled inside its steps, until the master accepts them (own_events.h) */
    ssx_own_event_list own_events;
    /* its declarative event handler (restart_handler.h), NULL for none */
    struct ssx_restart *restart;
};

extern const ssx_component_ops ssx_fmu_component_ops;

/* Unconnected inputs whose start is NaN take the value the initialized FMU holds. */
int fmu_component_adopt_inputs(ssx_system *sys, ssx_component *c, double t0);
/* Whether the FMU already holds every input value: nothing set it since the engine's last
 * write. */
int fmu_component_inputs_unchanged(const ssx_component *c);
/* Reads every output of an FMU component; a failure is reported at t, the time the FMU is at. */
int fmu_component_read_outputs_at(ssx_system *sys, ssx_component *c, double t);
/* A Model Exchange FMU integrated by the engine (me_component.c); its ports are an FMU
 * component's. */
extern const ssx_component_ops ssx_model_exchange_component_ops;
extern const ssx_component_ops ssx_python_component_ops;
extern const ssx_component_ops ssx_table_component_ops;

/* Dispatch: a Python hook if set, else the built-in. Each returns 0 or -1 with the error set. */
int component_do_step(ssx_system *sys, ssx_component *c, double t, double dt);
int component_write_inputs(ssx_system *sys, ssx_component *c);
int component_read_outputs(ssx_system *sys, ssx_component *c);
int component_evaluate_outputs(ssx_system *sys, ssx_component *c, double t);
int component_snapshot(ssx_system *sys, ssx_component *c, int slot);
int component_restore(ssx_system *sys, ssx_component *c, int slot, double t);
int component_handle_events(ssx_system *sys, ssx_component *c, const int *indicators, int n,
                            double t);
int component_initialize(ssx_system *sys, ssx_component *c, double t0);
int component_record(ssx_system *sys, ssx_component *c, double t);
int component_can_roll_back(const ssx_component *c);
/* Fails on the first NaN or infinite output, unless the system allows them. */
int component_check_outputs(ssx_system *sys, const ssx_component *c, double t);

/* Builds the per-type batches; called when the system initializes. */
int component_prepare(ssx_component *c);
void component_free(ssx_component *c);

#endif
