/* One FMU instance: the data every part of the framework shares. */
#ifndef SYSSIMX_FMU_INSTANCE_H
#define SYSSIMX_FMU_INSTANCE_H

#include <stddef.h>

#include "fmu_guid.h"
#include "fmu_status.h"
#include "model.h"

typedef enum {
    PHASE_INSTANTIATED,
    PHASE_INITIALIZATION,
    PHASE_STEP,
    PHASE_EVENT,           /* Model Exchange: event mode */
    PHASE_CONTINUOUS_TIME, /* Model Exchange: continuous-time mode */
    PHASE_TERMINATED,
    PHASE_FATAL /* after FMU_FATAL: no call is allowed any more */
} fmu_phase;

#define PHASE_BIT(phase) (1u << (phase))

/* Where each kind of fmi2 call is allowed (FMI 2.0 co-simulation and model exchange state
 * machines), one table for every entry point; PHASE_FATAL is in none of them. */
#define PHASES_RUNNING \
    (PHASE_BIT(PHASE_STEP) | PHASE_BIT(PHASE_EVENT) | PHASE_BIT(PHASE_CONTINUOUS_TIME))
#define PHASES_ANY                                                                 \
    (PHASE_BIT(PHASE_INSTANTIATED) | PHASE_BIT(PHASE_INITIALIZATION) | PHASES_RUNNING | \
     PHASE_BIT(PHASE_TERMINATED))
#define PHASES_SETTABLE \
    (PHASE_BIT(PHASE_INSTANTIATED) | PHASE_BIT(PHASE_INITIALIZATION) | PHASES_RUNNING)
#define PHASES_INITIALIZED (PHASE_BIT(PHASE_INITIALIZATION) | PHASES_RUNNING)
#define PHASES_STATUS (PHASE_BIT(PHASE_STEP) | PHASE_BIT(PHASE_TERMINATED))
/* Model Exchange */
#define PHASES_EVENT_OR_CONTINUOUS (PHASE_BIT(PHASE_EVENT) | PHASE_BIT(PHASE_CONTINUOUS_TIME))
#define PHASES_MODEL_EVALUATION \
    (PHASE_BIT(PHASE_INITIALIZATION) | PHASES_EVENT_OR_CONTINUOUS | PHASE_BIT(PHASE_TERMINATED))
#define PHASES_NOMINALS \
    (PHASE_BIT(PHASE_INSTANTIATED) | PHASES_EVENT_OR_CONTINUOUS | PHASE_BIT(PHASE_TERMINATED))

/* How the inputs move inside a step (fmu_interpolation.h). */
typedef enum {
    INPUTS_HELD,                /* constant, as set */
    INPUTS_POLYNOMIAL,          /* along the derivatives the importer set */
    INPUTS_INTERMEDIATE_UPDATE  /* as the importer answers FMI 3.0's intermediate update */
} input_motion_kind;

/* The importer's logger, as the FMI version's entry points received it. The core hands every
 * message to `forward`, the version's function that calls `logger` with its standard's types
 * and status (cast back from the untyped pointer kept here). */
typedef struct fmu_logging_callbacks {
    void (*forward)(const struct fmu_logging_callbacks *callbacks, const char *instance_name,
                    fmu_status status, const char *category, const char *message);
    void (*logger)(void); /* the importer's, NULL: none */
    void *environment;    /* what the importer's logger receives first */
} fmu_logging_callbacks;

typedef struct fmu_instance {
    /* What every Set, doStep and Get reads, in the instance's first cache line (the instance is
     * allocated aligned to one): where thousands of instances step in turn, each costs one
     * trip to memory here, not one per field. */
    fmu_phase phase;
    /* set when an input, a parameter, the state or the time changed since the outputs were last
     * computed: a get then recomputes them, otherwise it serves the values doStep computed */
    int outputs_stale;
    const model_definition *model;
    double *values;          /* by value reference; the line after the instance's last */
    double *x;               /* continuous states */
    double time;
    void *solver;            /* back-end data */
    /* Higher-order inputs (fmu_interpolation.h): per variable its first and second time
     * derivative (nonzero for Real inputs only), the inputs at the step's start, and FMI 3.0's
     * intermediate update (NULL when the importer gave no callback). Not part of the FMU state:
     * a restored state holds its inputs until the importer sets derivatives again. */
    input_motion_kind input_motion;
    int has_input_derivatives;
    void (*intermediate_update)(struct fmu_instance *inst, double t);
    /* the first line ends here */
    double step_start; /* of the step whose inputs follow their polynomial */
    double *input_derivatives; /* 2 per variable: first, then second derivatives */
    double *input_base;
    size_t n_variables;      /* model variables followed by the back-end's parameters */
    const model_variable *solver_variables;
    /* Internal events left to the importer (FMI 3.0 event mode with early return): a step
     * stops at the first one, which `fired` marks and event_pending keeps until the importer
     * applies it with fmu_apply_pending_events. in_event_mode: the importer entered FMI 3.0
     * Co-Simulation's Event Mode, during which the phase stays PHASE_STEP (a state taken there
     * belongs to a Co-Simulation instance; PHASE_EVENT is Model Exchange's). Both are part of
     * the FMU state; importer_handles_events is fixed at instantiation. */
    int importer_handles_events;
    int event_pending; /* 1, or EVENTS_HANDLED_IN_STEP: reported at the step's end only */
    int in_event_mode;
    fmu_phase running_phase; /* entered by exiting initialization mode: step or event mode */
    int tolerance_defined;
    double tolerance;
    /* scratch for derivatives and events, sized by the model */
    double *dx;
    double *z_before;
    double *z_after;
    int *fired;
    int *fired_in_step; /* events_at_step_end: the indicators that fired in the current step */
    /* Model Exchange: each indicator at the last event mode, or a positive value it took on the
     * trajectory since; part of the FMU state */
    double *z_previous;
    /* scratch for output derivatives: variable values and 2 * n_states */
    double *values_scratch;
    double *x_scratch;
    /* what only messages and states read */
    char *name;
    char guid[FMU_GUID_LENGTH]; /* computed once: states carry it to reject foreign bytes */
    fmu_logging_callbacks callbacks;
    int logging_on;
    unsigned log_categories; /* bit set of enabled categories (fmu_log.h) */
} fmu_instance;

/* Logs that `function` is not allowed in the instance's phase; returns NULL. */
fmu_instance *fmu_refuse_in_phase(fmu_instance *inst, const char *function);

/* The instance behind c when the call is allowed in one of the phases in `allowed` (a set of
 * PHASE_BIT); otherwise logs why and returns NULL. Inline: every entry point starts here. */
static inline fmu_instance *fmu_checked(void *c, const char *function, unsigned allowed)
{
    fmu_instance *inst = c;
    if (inst == NULL)
        return NULL;
    if ((allowed & PHASE_BIT(inst->phase)) == 0)
        return fmu_refuse_in_phase(inst, function);
    return inst;
}

const char *fmu_phase_name(fmu_phase phase);

/* A new instance of `size` bytes (at least sizeof(fmu_instance): an interface may extend it)
 * named and logging like `reporter`, at its start values with its back-end created; NULL after
 * reporting the failure through `reporter`. `function` names the call in messages. */
fmu_instance *fmu_instance_create(const fmu_instance *reporter, size_t size,
                                  const char *function);
void fmu_instance_free(fmu_instance *inst);

/* The lifecycle steps every interface shares; `function` names the call in messages. */
fmu_status fmu_setup_experiment(fmu_instance *inst, const char *function, int tolerance_defined,
                                double tolerance, double start_time, int stop_time_defined,
                                double stop_time);
void fmu_exit_initialization(fmu_instance *inst);
void fmu_reset(fmu_instance *inst);
/* Forgets every input derivative: the inputs are held again (reset, a restored state). */
void fmu_hold_inputs(fmu_instance *inst);

/* The table row of a value reference, or NULL when the FMU has no such variable. Inline: every
 * get and set checks each of its value references with it. */
static inline const model_variable *fmu_variable(const fmu_instance *inst, unsigned int vr)
{
    size_t n_model = inst->model->n_variables;
    if (vr < n_model)
        return &inst->model->variables[vr];
    if (vr < inst->n_variables)
        return &inst->solver_variables[vr - n_model];
    return NULL;
}

/* Every variable back to its start value, the states from the parameters, time to zero. */
void fmu_apply_start_values(fmu_instance *inst);

/* The status a model's refusal (model.h) returns; after FMU_FATAL no call is allowed any more. */
fmu_status fmu_refusal_status(fmu_instance *inst, step_refusal_kind kind);

/* event_pending's value for events a model with events_at_step_end handled inside the step:
 * the importer is told of them at the step's end, and they are not applied again. */
enum { EVENTS_HANDLED_IN_STEP = 2 };

/* Apply the event a step stopped at (event_pending) at the instance's time; restarts the
 * integration there. Returns whether a continuous state changed. */
int fmu_apply_pending_events(fmu_instance *inst);

#endif
