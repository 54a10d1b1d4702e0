/* The FMU kinds' own data and the functions the two kinds (Co-Simulation: fmu_component.c,
 * Model Exchange: me_component.c) share. Other rooms reach an FMU component only through the
 * component interface or the functions here that take any component. */
#ifndef SSX_FMU_COMPONENT_H
#define SSX_FMU_COMPONENT_H

#include <stddef.h>

#include "component.h"
#include "fmu_binding.h"
#include "restart_handler.h"

/* Ports of one value type, batched for a single Get/Set call. */
typedef struct {
    unsigned int *vr;
    int *port; /* index of each entry in the component's port array */
    size_t n;
} fmu_port_batch;

/* What an FMU component holds besides the ports: c->data of both FMU kinds starts with it
 * (the Model Exchange kind's data embeds it as its first member). */
typedef struct {
    /* What every step reads, in the data's first two cache lines (the data starts on one):
     * where thousands of components step in turn, each line is a trip to memory. The batches
     * are built at initialization. */
    ssx_fmu *fmu; /* borrowed */
    /* the inputs as last written to the FMU and its values epoch right after that write
     * (-1: nothing written yet); equal inputs at an unchanged epoch need no Set call */
    long inputs_written_epoch;
    double *inputs_written;
    double *real_scratch;
    fmu_port_batch real_outputs;
    int has_discrete_ports; /* Integer or Boolean ports: their batches are read too */
    fmu_port_batch real_inputs;
    int *int_scratch;
    fmu_port_batch discrete_outputs[2]; /* Integer, Boolean: [type - SSX_INTEGER] */
    fmu_port_batch discrete_inputs[2];
    /* one block holding the batches' arrays, the scratch and inputs_written */
    void *step_block;
    ssx_component_capabilities capabilities;
    /* one reused FMU state per snapshot slot, valid for one instance generation */
    void *fmu_state[SSX_SNAPSHOT_SLOTS];
    long fmu_state_generation[SSX_SNAPSHOT_SLOTS];
    /* the input derivatives as the FMU takes them, grown to the largest write */
    unsigned int *derivative_vr;
    int *derivative_order;
    double *derivative_values;
    size_t derivative_capacity;
    ssx_restart *restart; /* its declarative event handler, NULL for none */
    /* String ports (their values are numbers in the system's text table) and the FMU's texts
     * of one batch, built at initialization */
    fmu_port_batch text_outputs;
    fmu_port_batch text_inputs;
    const char **text_scratch;
    /* the same for Binary ports (FMI 3.0): their bytes and sizes */
    fmu_port_batch binary_outputs;
    fmu_port_batch binary_inputs;
    const unsigned char **binary_scratch;
    size_t *size_scratch;
} fmu_component_data;

static inline fmu_component_data *fmu_data(const ssx_component *c)
{
    return (fmu_component_data *)c->data;
}

/* Sets up the data of a new FMU component of either kind; frees what it holds. */
void fmu_component_data_init(fmu_component_data *d, ssx_fmu *fmu);
void fmu_component_data_free(fmu_component_data *d);

/* c's FMU when its kind runs one (ops->fmu), else NULL. */
ssx_fmu *fmu_component_binding(const ssx_component *c);

/* The FMU kinds' shared operations (component.h describes each). */
int fmu_component_prepare(ssx_system *sys, ssx_component *c);
void fmu_component_unprepare(ssx_component *c);
ssx_fmu *fmu_component_fmu(const ssx_component *c);
int fmu_component_adopt_inputs(ssx_system *sys, ssx_component *c, double t0);
int fmu_component_directional_derivative(ssx_system *sys, ssx_component *c,
                                         const unsigned int *outputs, size_t n_outputs,
                                         const unsigned int *inputs, size_t n_inputs,
                                         const double *seed, double *out, double t);
const void *fmu_component_instance(const ssx_component *c);
ssx_component_capabilities fmu_component_capabilities(const ssx_component *c);
int fmu_component_output_derivatives(ssx_system *sys, ssx_component *c, double t, double *slope);
int fmu_component_set_input_derivatives(ssx_system *sys, ssx_component *c, int order,
                                        const double *derivatives);
int fmu_component_can_roll_back(const ssx_component *c);
int fmu_component_handle_events(ssx_system *sys, ssx_component *c, double t);
/* Whether the FMU already holds every input value: nothing set it since the engine's last
 * write. */
int fmu_component_inputs_unchanged(const ssx_component *c);
/* Reads every output of an FMU component; a failure is reported at t, the time the FMU is at. */
int fmu_component_read_outputs_at(ssx_system *sys, ssx_component *c, double t);
/* The FMU kinds' initial_outputs and leave_initialization (component.h). */
int fmu_component_initial_outputs(ssx_system *sys, ssx_component *c, double t0);
int fmu_component_leave_initialization(ssx_system *sys, ssx_component *c, double t0);

/* The FMU kinds' state by handle (component_state_ops): their FMU's state, of the instance it
 * was taken from. The Model Exchange kind adds its own to it. */
typedef struct {
    ssx_fmu *fmu;
    void *fmu_state;
    long generation;
} fmu_saved_state;
int fmu_state_save_into(ssx_system *sys, ssx_component *c, fmu_saved_state *s);
int fmu_state_restore_from(ssx_system *sys, ssx_component *c, const fmu_saved_state *s, double t);
void fmu_state_release(fmu_saved_state *s);
int fmu_state_write(ssx_system *sys, ssx_component *c, const fmu_saved_state *s,
                    struct byte_writer *out);
int fmu_state_read(ssx_system *sys, ssx_component *c, struct byte_reader *in,
                   fmu_saved_state *s);

#endif
