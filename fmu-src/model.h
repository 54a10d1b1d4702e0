/* What a model provides to the FMU framework: its variable table and its equations.
 *
 * A model is one C file that defines `fmu_model` (see the models/ folders). The framework serves
 * every FMI function (1.0, 2.0 and 3.0), the solver back-ends integrate the equations, and the
 * describe tool writes modelDescription.xml, all from this one definition. */
#ifndef SYSSIMX_FMU_MODEL_H
#define SYSSIMX_FMU_MODEL_H

#include <stddef.h>

typedef enum { TYPE_REAL, TYPE_INTEGER, TYPE_BOOLEAN } variable_type;

typedef enum {
    CAUSALITY_PARAMETER,
    CAUSALITY_INPUT,
    CAUSALITY_OUTPUT,
    CAUSALITY_LOCAL
} variable_causality;

typedef enum {
    VARIABILITY_FIXED,
    VARIABILITY_TUNABLE,
    VARIABILITY_DISCRETE,
    VARIABILITY_CONTINUOUS
} variable_variability;

typedef enum { INITIAL_NONE, INITIAL_EXACT, INITIAL_CALCULATED } variable_initial;

/* A dependency list: value references ended by DEPENDS_END. */
#define DEPENDS_END (-1)
#define DEPENDS(...) ((const int[]){__VA_ARGS__, DEPENDS_END})
#define DEPENDS_NONE ((const int[]){DEPENDS_END})

/* One row of the variable table. The value reference is the row's index in the table. */
typedef struct {
    const char *name;
    unsigned vr;
    variable_type type;
    variable_causality causality;
    variable_variability variability;
    variable_initial initial;
    const char *unit;        /* NULL: dimensionless */
    double start;            /* used when initial is exact or for inputs */
    const char *description;
    int derivative_of;       /* vr of the state this variable is the derivative of, or -1 */
    /* For outputs and derivatives: the inputs and states the value depends on in step mode,
     * and the parameters and inputs it depends on at initialization. */
    const int *depends;
    const int *initial_depends;
    /* NULL: modelDescription.xml declares `start` exactly. Otherwise the text it declares
     * instead, for test models that mimic exporters printing starts rounded (e.g. "%f"). */
    const char *declared_start;
    /* 0: not clocked; otherwise 1 + the index of the model's clock (FMI 3.0 only) at whose
     * ticks alone the variable changes */
    int clock;
} model_variable;

/* The rows of the variable table, one macro per kind of variable, each naming the fields it
 * sets; the others are zero (no unit, start 0). `vr` is the value reference and the row's
 * index; `depends` and `initial_depends` are DEPENDS(...), DEPENDS_NONE or NULL (none
 * declared); `state` is the value reference of the state a derivative belongs to. */
#define MODEL_ROW(vr_, name_, type_, causality_, variability_, initial_, derivative_of_, ...)     \
    [vr_] = {.name = (name_), .vr = (vr_), .type = (type_), .causality = (causality_),            \
             .variability = (variability_), .initial = (initial_),                                \
             .derivative_of = (derivative_of_), __VA_ARGS__}

/* A fixed parameter with initial="exact". */
#define REAL_PARAMETER(vr, name, unit_, start_, description_)                                     \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_PARAMETER, VARIABILITY_FIXED, INITIAL_EXACT, -1,     \
              .unit = (unit_), .start = (start_), .description = (description_))
#define INTEGER_PARAMETER(vr, name, start_, description_)                                         \
    MODEL_ROW(vr, name, TYPE_INTEGER, CAUSALITY_PARAMETER, VARIABILITY_FIXED, INITIAL_EXACT, -1,  \
              .start = (start_), .description = (description_))

/* A continuous input. */
#define REAL_INPUT(vr, name, unit_, start_, description_)                                         \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_INPUT, VARIABILITY_CONTINUOUS, INITIAL_NONE, -1,     \
              .unit = (unit_), .start = (start_), .description = (description_))

/* A parameter or an input whose modelDescription.xml declares the text `declared` instead of
 * its start, for test models that mimic exporters printing starts rounded (e.g. "%f"). */
#define REAL_PARAMETER_DECLARED(vr, name, unit_, start_, declared, description_)                  \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_PARAMETER, VARIABILITY_FIXED, INITIAL_EXACT, -1,     \
              .unit = (unit_), .start = (start_), .description = (description_),                  \
              .declared_start = (declared))
#define REAL_INPUT_DECLARED(vr, name, unit_, start_, declared, description_)                      \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_INPUT, VARIABILITY_CONTINUOUS, INITIAL_NONE, -1,     \
              .unit = (unit_), .start = (start_), .description = (description_),                  \
              .declared_start = (declared))

/* A continuous output computed from the states, inputs and parameters. */
#define REAL_OUTPUT(vr, name, unit_, description_, depends_, initial_depends_)                    \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_OUTPUT, VARIABILITY_CONTINUOUS,                      \
              INITIAL_CALCULATED, -1,                                                             \
              .unit = (unit_), .description = (description_), .depends = (depends_),              \
              .initial_depends = (initial_depends_))

/* A continuous output that is the derivative of `state` (an acceleration as an output). */
#define REAL_DERIVATIVE_OUTPUT(vr, name, unit_, description_, state, depends_, initial_depends_)  \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_OUTPUT, VARIABILITY_CONTINUOUS,                      \
              INITIAL_CALCULATED, state,                                                          \
              .unit = (unit_), .description = (description_), .depends = (depends_),              \
              .initial_depends = (initial_depends_))

/* An output that changes only at events. */
#define REAL_DISCRETE_OUTPUT(vr, name, unit_, description_, depends_, initial_depends_)           \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_OUTPUT, VARIABILITY_DISCRETE, INITIAL_CALCULATED, -1,\
              .unit = (unit_), .description = (description_), .depends = (depends_),              \
              .initial_depends = (initial_depends_))
#define BOOLEAN_DISCRETE_OUTPUT(vr, name, description_, depends_, initial_depends_)               \
    MODEL_ROW(vr, name, TYPE_BOOLEAN, CAUSALITY_OUTPUT, VARIABILITY_DISCRETE,                     \
              INITIAL_CALCULATED, -1,                                                             \
              .description = (description_), .depends = (depends_),                               \
              .initial_depends = (initial_depends_))

/* A continuous local computed from the states (a state shown by a variable of its own). */
#define REAL_LOCAL(vr, name, unit_, description_, depends_, initial_depends_)                     \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_LOCAL, VARIABILITY_CONTINUOUS, INITIAL_CALCULATED, -1,\
              .unit = (unit_), .description = (description_), .depends = (depends_),              \
              .initial_depends = (initial_depends_))

/* The derivative of `state` as a local ("der(x)"). */
#define REAL_DERIVATIVE(vr, name, unit_, description_, state, depends_, initial_depends_)         \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_LOCAL, VARIABILITY_CONTINUOUS,                       \
              INITIAL_CALCULATED, state,                                                          \
              .unit = (unit_), .description = (description_), .depends = (depends_),              \
              .initial_depends = (initial_depends_))

/* A discrete output or local that changes only at the ticks of clock `clock_index` (FMI 3.0
 * clocked variables), `start_` until the first tick. */
#define REAL_CLOCKED_OUTPUT(vr, name, unit_, start_, description_, clock_index, depends_)         \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_OUTPUT, VARIABILITY_DISCRETE, INITIAL_EXACT, -1,     \
              .unit = (unit_), .start = (start_), .description = (description_),                  \
              .depends = (depends_), .clock = (clock_index) + 1)
#define REAL_CLOCKED_LOCAL(vr, name, unit_, start_, description_, clock_index)                    \
    MODEL_ROW(vr, name, TYPE_REAL, CAUSALITY_LOCAL, VARIABILITY_DISCRETE, INITIAL_EXACT, -1,      \
              .unit = (unit_), .start = (start_), .description = (description_),                  \
              .clock = (clock_index) + 1)

/* What ticks a clock (FMI 3.0). CLOCK_PERIODIC: an input clock (intervalVariability
 * "constant") the importer ticks every `interval` seconds from the start time. CLOCK_TRIGGERED:
 * an input clock (intervalVariability "triggered") the importer ticks when it likes. Both apply
 * at fmi3UpdateDiscreteStates in Event Mode. CLOCK_OUTPUT: an output clock that ticks when the
 * model's internal event `indicator` fires (the step returns early there; the importer reads
 * it with fmi3GetClock in Event Mode). CLOCK_COUNTDOWN: an input clock (intervalVariability
 * "countdown") whose next tick the model announces: the importer asks for its interval
 * (fmi3GetIntervalDecimal) in Initialization and Event Mode, and ticks it that long after.
 * CLOCK_CHANGING: the same, intervalVariability "changing": the clock ticks every announced
 * interval until the model announces another. */
typedef enum {
    CLOCK_PERIODIC = 0, CLOCK_TRIGGERED, CLOCK_OUTPUT, CLOCK_COUNTDOWN, CLOCK_CHANGING
} model_clock_kind;

typedef struct {
    const char *name;
    const char *description;
    double interval; /* CLOCK_PERIODIC only */
    model_clock_kind kind;
    int indicator; /* CLOCK_OUTPUT only */
} model_clock;

/* How a refused step fails: the step fails and may be retried (FMU_ERROR), or the step could
 * not be completed (FMU_DISCARD: the FMU stays at the step's start), or the model is broken for
 * good (FMU_FATAL: every later call is refused). */
typedef enum { STEP_FAILS, STEP_DISCARDED, STEP_FATAL } step_refusal_kind;

/* Equations. `v` holds every variable by value reference (Integer and Boolean values as
 * doubles); `x` is the continuous state vector. */
typedef struct {
    const char *name;
    const char *description;
    const model_variable *variables;
    size_t n_variables;
    size_t n_states;
    const unsigned *state_vrs;  /* the variable that shows each state, in state order */
    size_t n_event_indicators;  /* internal events, handled inside the FMU */
    /* FMI 3.0 Co-Simulation without early return (mightReturnEarlyFromDoStep false): the
     * internal events are handled inside the step, and those that tick an output clock are
     * reported at the step's end (eventHandlingNeeded, then fmi3GetClock in Event Mode), as
     * tools that cannot return early do */
    int events_at_step_end;
    double default_stop_time;
    double default_step_size;

    /* states at the start time, from the parameters */
    void (*initial_states)(const double *v, double *x);
    void (*derivatives)(const double *v, double t, const double *x, double *dx);
    /* outputs and locals from the state and the current inputs */
    void (*outputs)(double *v, double t, const double *x);
    /* indicator i fires when it falls from > 0 to <= 0; Model Exchange serves these values as
     * its event indicators */
    void (*event_indicators)(const double *v, double t, const double *x, double *z);
    /* apply the events marked in fired[]; may change x and discrete variables in v */
    void (*handle_events)(double *v, double t, double *x, const int *fired);
    /* NULL when the model can always step; otherwise a reason to refuse a step ending at t_end,
     * and in *kind how the refusal fails (set to STEP_FAILS only when it is not the default).
     * Model Exchange refuses fmi2SetTime(t_end) the same way. */
    const char *(*step_refusal)(const double *v, double t_end, step_refusal_kind *kind);
    /* NULL when the model never asks to stop; otherwise the time at which it asks the master to
     * end the simulation (INFINITY: not now). A step stops there (FMI 2.0: fmi2Discard,
     * and fmi2GetBooleanStatus(fmi2Terminated) then answers true). Model Exchange reports it as
     * nextEventTime, and event mode there answers terminateSimulation. */
    double (*termination_time)(const double *v);
    /* NULL when the model has no time events; otherwise the first time after t at which its
     * discrete variables change (INFINITY: none). Model Exchange reports it as nextEventTime;
     * the time events are instants where an importer must stop and enter event mode. */
    double (*next_time_event)(const double *v, double t);
    /* NULL when values can always be read; otherwise a reason to refuse fmi2Get* at time t */
    const char *(*read_refusal)(const double *v, double t);
    /* NULL when not provided; otherwise d output / d input at the current point with the states
     * held fixed (the feedthrough Jacobian a co-simulation master needs at a communication
     * point), for any output and input value reference. Serves fmi2GetDirectionalDerivative. */
    double (*partial_derivative)(const double *v, const double *x, unsigned output,
                                 unsigned input);
    /* FMI 3.0 only: the model's clocks, and the update of its clocked variables when the
     * input clocks marked in active[] tick at time t (the inputs are those set at the tick);
     * variables clocked by an output clock change in handle_events */
    const model_clock *clocks;
    size_t n_clocks;
    void (*clock_tick)(double *v, double t, const int *active);
    /* CLOCK_COUNTDOWN and CLOCK_CHANGING clocks: the interval to the next tick of clock
     * `clock`, and in *changed whether it is newly announced (the model forgets that it
     * announced it) */
    double (*clock_interval)(double *v, size_t clock, int *changed);
} model_definition;

extern const model_definition fmu_model;

#endif
