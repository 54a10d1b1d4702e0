/* syssimx engine: the public C API.
 *
 * The build turns this very file into Python's cffi module (out-of-line ABI mode,
 * src/engine_ffi.py): every line that starts with '#' is dropped, so the declarations below
 * must stay plain C that cffi parses (no macros, no inline code, no variadic functions).
 *
 * Conventions
 * - Calls returning int return 0 on success and -1 on failure; the failure is described by
 *   ssx_last_error(). The ssx_fmu_* wrappers of single fmi2 calls return the fmi2Status
 *   (0 OK, 1 Warning, 2 Discard, 3 Error, 4 Fatal, 5 Pending) or -1 when the engine itself failed.
 * - Components, outputs, inputs and indicators are numbered from 0 in the order they are added.
 * - All port values live in the engine as doubles; Integer and Boolean ports are converted at
 *   the fmi2 boundary.
 * - No global mutable state: everything hangs off an ssx_fmu or an ssx_system.
 */
#ifndef SYSSIMX_ENGINE_H
#define SYSSIMX_ENGINE_H

#include <stddef.h>
#include <stdint.h>

/* SSX_STRING, SSX_BINARY: an FMU's String or (FMI 3.0) Binary variable; the port's value is
 * the number of its text or bytes in the system's text table (ssx_text_number, ssx_text). */
typedef enum {
    SSX_REAL = 0,
    SSX_INTEGER = 1,
    SSX_BOOLEAN = 2,
    SSX_STRING = 3,
    SSX_BINARY = 4
} ssx_value_type;
typedef enum { SSX_GAUSS_SEIDEL = 0, SSX_JACOBI = 1 } ssx_coupling;
/* Event localization. SSX_ILLINOIS: Illinois (modified regula falsi) held within two trials of
 * bisection's count; SSX_BISECTION; SSX_ILLINOIS_UNGUARDED: Illinois alone, for comparison. */
typedef enum { SSX_ILLINOIS = 0, SSX_BISECTION = 1, SSX_ILLINOIS_UNGUARDED = 2 } ssx_locator;
typedef enum { SSX_JACOBIAN_AUTO = 0, SSX_JACOBIAN_FINITE_DIFFERENCES = 1 } ssx_loop_jacobian;

/* The options a new system starts with: the one definition of every default, read by Python
 * (ssx_get_defaults) for its algorithm classes. */
typedef struct {
    ssx_coupling coupling;
    double loop_tolerance;
    int loop_max_iterations;
    double loop_damping;
    ssx_loop_jacobian loop_jacobian;
    double tol_time;
    double tol_value;
    int max_iterations; /* localization iterations per event */
    int max_microsteps;
    ssx_locator locator;
    double zeno_min_interval; /* 0: the rule of ssx_set_hybrid_options */
    int output_interval;
    /* CVODE's relative tolerance for a Model Exchange FMU set up without one (FMPy's) */
    double model_exchange_tolerance;
    int threads; /* threads that step FMU components (ssx_set_threads) */
    int input_order; /* ssx_set_input_order */
    int extrapolate_held_inputs; /* ssx_set_extrapolate_held_inputs */
    /* ssx_set_step_control (off by default) */
    double step_rtol;
    double step_atol;
    double step_min;
    double step_safety;
    double step_min_change;
    double step_max_change;
    double step_proportional_gain;
    double step_integral_gain;
} ssx_defaults;
void ssx_get_defaults(ssx_defaults *out);

/* The SHA-256 (hex) of the header this library was built from; Python's cffi module holds the
 * digest of the header it was generated from, and refuses a library whose digest differs. */
const char *ssx_interface_digest(void);

/* ------------------------------------------------------------------------------------------
 * One loaded FMU binary with (at most) one live instance. Owned by the Python FMUComponent,
 * borrowed by every system it is added to.
 * ------------------------------------------------------------------------------------------ */
typedef struct ssx_fmu ssx_fmu;

typedef struct {
    long do_step;
    long get_state;
    long set_state;
    long get_values;   /* fmi2Get* calls, any type */
    long set_values;   /* fmi2Set* calls, any type */
    long instantiate;
    long directional_derivative; /* fmi2GetDirectionalDerivative calls */
    long reset;        /* fmi2Reset calls, ssx_fmu_initialize's reuse of a live instance too */
} ssx_fmu_counters;

void ssx_fmu_free(ssx_fmu *fmu); /* terminates/frees a live instance, then unloads */

/* FMI 3.0 Co-Simulation. The engine keeps its three port types: Float64 and Float32 variables
 * are Real ports, Int8 ... UInt64 Integer ports (a value outside the int range fails the call
 * that meets it, naming the variable), Boolean ones Boolean ports. An integer variable may be
 * exchanged as a Real port instead: exact up to 2^53 in magnitude, a value beyond fails
 * naming the variable (syssimx does so for UInt32, Int64 and UInt64). The
 * back-end batches each engine call into one fmi3Get/Set call per FMI 3.0 type, by the table
 * given at load. */
typedef enum {
    SSX_FMI3_FLOAT64 = 0, SSX_FMI3_FLOAT32, SSX_FMI3_INT8, SSX_FMI3_UINT8, SSX_FMI3_INT16,
    SSX_FMI3_UINT16, SSX_FMI3_INT32, SSX_FMI3_UINT32, SSX_FMI3_INT64, SSX_FMI3_UINT64,
    SSX_FMI3_BOOLEAN, SSX_FMI3_TYPE_COUNT
} ssx_fmi3_type;

/* Every scalar variable the engine may get or set: value reference, ssx_fmi3_type and name
 * (for messages), n of each; and how the instance is made: eventModeUsed (the FMU declares
 * hasEventMode) and earlyReturnAllowed (it declares canReturnEarlyAfterIntermediateUpdate or
 * mightReturnEarlyFromDoStep). */
typedef struct {
    const unsigned int *vr;
    const unsigned char *type;
    const char *const *name;
    size_t n;
    int event_mode_used;
    int early_return_allowed;
    /* Array elements; all NULL when every variable is a scalar. size[i] == 0: variable i is a
     * scalar (vr[i] is the FMU's). Otherwise vr[i] is the engine's own reference for element
     * element[i] (row-major) of the FMU's array variable fmu_vr[i] of size[i] elements, whose
     * start value is start[i]. The back-end reads and writes each array whole, in one call,
     * completing the elements not written with their last value written (start until then). */
    const unsigned int *fmu_vr;
    const size_t *element;
    const size_t *size;
    const double *start;
    /* Co-Simulation with providesIntermediateUpdate: the scalar Float64 inputs the FMU lets the
     * importer set in intermediate update (intermediateUpdate="true"). With any, the instance
     * is made with them as requiredIntermediateVariables, and ssx_fmu_set_real_input_derivatives
     * moves them inside each step: the callback answers with their Taylor polynomial from the
     * communication point. NULL / 0: none. */
    const unsigned int *intermediate_vr;
    size_t n_intermediate;
    /* Co-Simulation: the periodic input clocks (intervalVariability constant or fixed) the
     * engine ticks at start + shift + k * period, k = 0, 1, ...: doStep ends at each tick and
     * the instance, made with event mode, ticks there (fmi3SetClock, fmi3UpdateDiscreteStates).
     * NULL / 0: none. */
    const unsigned int *clock_vr;
    const double *clock_period;
    const double *clock_shift;
    size_t n_clocks;
    /* Co-Simulation with event mode: the triggered input clocks (intervalVariability
     * triggered), which tick when a source connected to them fires (ssx_connect_clock), and
     * the output clocks, read (fmi3GetClock) in every Event Mode of the instance: each that
     * ticks is an own event of the component (SSX_OWN_OUTPUT_CLOCK). NULL / 0: none. */
    const unsigned int *triggered_clock_vr;
    size_t n_triggered_clocks;
    const unsigned int *output_clock_vr;
    size_t n_output_clocks;
    /* Co-Simulation with event mode: the countdown input clocks (intervalVariability
     * countdown). After Initialization Mode and after every Event Mode the engine asks for their
     * interval (fmi3GetIntervalDecimal); each the FMU newly announces ticks that long after, the
     * FMU's step ending there as at a periodic tick. NULL / 0: none. */
    const unsigned int *countdown_clock_vr;
    size_t n_countdown_clocks;
    /* 1 for a countdown clock that repeats (intervalVariability tunable or changing): after a
     * tick it ticks again one interval later, until the FMU announces another. NULL: none. */
    const unsigned char *countdown_clock_repeats;
} ssx_fmi3_variables;

/* The FMI standard and the interface a binary is loaded as. */
typedef enum { SSX_FMI1 = 1, SSX_FMI2 = 2, SSX_FMI3 = 3 } ssx_fmi_version;
typedef enum {
    SSX_CO_SIMULATION = 0,
    SSX_MODEL_EXCHANGE = 1,
    SSX_SCHEDULED_EXECUTION = 2 /* FMI 3.0 only: ssx_fmu_activate_model_partition */
} ssx_fmu_interface;

/* Where bindings are made: those loaded with one pool lie next to each other in the order they
 * were loaded, a few to a page, instead of between the other allocations of each load. A system
 * of thousands of FMUs then reaches its bindings, one per step of each, through a few pages.
 * The pool lives until it is released and its last binding freed, in either order. */
typedef struct ssx_binding_pool ssx_binding_pool;
ssx_binding_pool *ssx_binding_pool_new(void); /* NULL when out of memory */
void ssx_binding_pool_release(ssx_binding_pool *pool);

/* What loading a binary needs. The texts and the variables are copied. */
typedef struct {
    ssx_fmi_version version;
    ssx_fmu_interface interface; /* a Model Exchange instance is integrated by the engine: its
                                  * component is added with ssx_add_model_exchange_component */
    const char *binary_path;
    const char *model_identifier; /* the interface's: names the binary and prefixes names */
    const char *guid;             /* FMI 3.0: the instantiation token */
    /* what the standard passes at instantiation: FMI 2.0 the resources folder's URI, FMI 3.0
     * its path ending in '/', FMI 1.0 Co-Simulation the URI of the extracted archive */
    const char *resource_location;
    const char *instance_name; /* NULL: the model identifier */
    int logging_on;
    /* non-NULL: the binary runs in a host process (the syssimx-fmu-host executable installed
     * beside the engine library; FMI 2.0 Co-Simulation only), see Isolation below */
    const char *host_path;
    double step_timeout;
    const ssx_fmi3_variables *fmi3_variables; /* FMI 3.0 only */
    ssx_binding_pool *binding_pool; /* NULL: the binding is allocated on its own */
} ssx_fmu_load_spec;

/* Loads the binary (dlopen RTLD_NOW | RTLD_LOCAL, or in a host process) and resolves the
 * functions of the spec's standard and interface (prefixed with the model identifier, as
 * "<id>_<name>", when unprefixed names are missing; FMI 1.0 always prefixes). Does not
 * instantiate. On failure returns NULL and writes the reason into error. */
ssx_fmu *ssx_fmu_load(const ssx_fmu_load_spec *spec, char *error, size_t error_size);
/* fmi3Get/SetString and fmi3Get/SetBinary (FMI 3.0 only: other FMUs refuse them). The texts
 * and bytes read stay valid until the next call on the FMU. */
int ssx_fmu_get_string(ssx_fmu *fmu, const unsigned int *vr, size_t n, const char **values);
int ssx_fmu_set_string(ssx_fmu *fmu, const unsigned int *vr, size_t n, const char *const *values);
int ssx_fmu_get_binary(ssx_fmu *fmu, const unsigned int *vr, size_t n, size_t *sizes,
                       const unsigned char **values);
int ssx_fmu_set_binary(ssx_fmu *fmu, const unsigned int *vr, size_t n, const size_t *sizes,
                       const unsigned char *const *values);
/* FMI 3.0 Scheduled Execution (loaded with SSX_SCHEDULED_EXECUTION, initialized into Clock
 * Activation Mode): runs the model partition of input clock `clock` at t. While it runs, each
 * clockUpdate callback of the FMU reads the output clocks (fmi3GetClock) and the countdown
 * clocks' intervals (fmi3GetIntervalDecimal) of the load spec; the preemption lock must be
 * balanced when it returns, else the call fails. */
int ssx_fmu_activate_model_partition(ssx_fmu *fmu, unsigned int clock, double t);
/* What the partitions run since the last take announced, then forgotten: ticked[k] (one per
 * output clock of the load spec) whether output clock k ticked, next[i] (one per countdown
 * clock) the time countdown clock i is to tick, INFINITY when none was announced. */
void ssx_fmu_take_clock_updates(ssx_fmu *fmu, int *ticked, double *next);
/* fmi3GetIntervalDecimal of one clock: its interval and qualifier (SSX_INTERVAL_CHANGED when
 * the FMU gives a new one). */
enum { SSX_INTERVAL_NOT_YET_KNOWN = 0, SSX_INTERVAL_UNCHANGED = 1, SSX_INTERVAL_CHANGED = 2 };
int ssx_fmu_get_interval(ssx_fmu *fmu, unsigned int clock, double *interval, int *qualifier);
/* How many countdown clocks the load spec gave (0 for other back-ends). */
size_t ssx_fmu_countdown_clock_count(const ssx_fmu *fmu);

/* The name of a status an ssx_fmu_* call returned, without its standard's prefix: "OK",
 * "Warning", "Discard", "Error", "Fatal", "Pending", and "failed" for -1; NULL for any other. */
const char *ssx_status_name(int status);

/* What ssx_fmu_initialize writes in initialization mode: values by type, n_* value references
 * and as many values each (a Boolean is 0 or 1). */
typedef struct {
    const unsigned int *real_vr;
    const double *real_values;
    size_t n_real;
    const unsigned int *integer_vr;
    const int *integer_values;
    size_t n_integer;
    const unsigned int *boolean_vr;
    const int *boolean_values;
    size_t n_boolean;
} ssx_fmu_values;

/* The experiment an instance is set up for; a tolerance or stop time that is not defined is
 * not passed on (the FMU chooses). */
typedef struct {
    double start_time;
    int tolerance_defined;
    double tolerance;
    int stop_time_defined;
    double stop_time;
} ssx_fmu_experiment;

/* An instance ready to step from its start values: a live instance is reset (fmi2Reset,
 * fmi3Reset: the FMU is as just instantiated, its FMU states stay valid), else, or when the
 * reset fails, instantiated (a live instance is freed first); then set up the experiment, enter initialization mode, write `starts` (NULL: none) by type, call
 * in_initialization_mode(user) when it is not NULL (it may write more values; nonzero fails
 * the call and its caller keeps the reason), exit initialization mode. Returns the highest
 * status of the sequence (0 OK or 1 Warning), else the status of the call that failed (-1:
 * the engine failed or the callback did); ssx_fmu_last_call names that call. */
int ssx_fmu_initialize(ssx_fmu *fmu, const ssx_fmu_experiment *experiment,
                       const ssx_fmu_values *starts, int (*in_initialization_mode)(void *user),
                       void *user);
/* ssx_fmu_initialize without its last call: the instance stays in initialization mode, for
 * ssx_initialize to give it its connected inputs and make it leave (the system's
 * initial-value problem). */
int ssx_fmu_enter_initialization(ssx_fmu *fmu, const ssx_fmu_experiment *experiment,
                                 const ssx_fmu_values *starts,
                                 int (*in_initialization_mode)(void *user), void *user);
int ssx_fmu_instantiate(ssx_fmu *fmu); /* a live instance is freed first */
int ssx_fmu_free_instance(ssx_fmu *fmu);
int ssx_fmu_setup_experiment(ssx_fmu *fmu, int tolerance_defined, double tolerance,
                             double start_time, int stop_time_defined, double stop_time);
int ssx_fmu_enter_initialization_mode(ssx_fmu *fmu);
int ssx_fmu_exit_initialization_mode(ssx_fmu *fmu);
int ssx_fmu_do_step(ssx_fmu *fmu, double t, double h, int no_set_fmu_state_prior);
int ssx_fmu_get_real(ssx_fmu *fmu, const unsigned int *vr, size_t n, double *values);
int ssx_fmu_set_real(ssx_fmu *fmu, const unsigned int *vr, size_t n, const double *values);
int ssx_fmu_get_integer(ssx_fmu *fmu, const unsigned int *vr, size_t n, int *values);
int ssx_fmu_set_integer(ssx_fmu *fmu, const unsigned int *vr, size_t n, const int *values);
int ssx_fmu_get_boolean(ssx_fmu *fmu, const unsigned int *vr, size_t n, int *values);
int ssx_fmu_set_boolean(ssx_fmu *fmu, const unsigned int *vr, size_t n, const int *values);
int ssx_fmu_get_state(ssx_fmu *fmu, void **state); /* *state != NULL: reuse that state */
int ssx_fmu_set_state(ssx_fmu *fmu, void *state);
int ssx_fmu_free_state(ssx_fmu *fmu, void **state);
int ssx_fmu_serialized_state_size(ssx_fmu *fmu, void *state, size_t *size);
int ssx_fmu_serialize_state(ssx_fmu *fmu, void *state, char *bytes, size_t size);
int ssx_fmu_deserialize_state(ssx_fmu *fmu, const char *bytes, size_t size, void **state);
int ssx_fmu_get_directional_derivative(ssx_fmu *fmu, const unsigned int *unknowns, size_t n_unknowns,
                                       const unsigned int *knowns, size_t n_knowns,
                                       const double *dv_known, double *dv_unknown);
/* Input and output derivatives (FMI 2.0 canInterpolateInputs, maxOutputDerivativeOrder; FMI
 * 3.0 has output derivatives only). */
int ssx_fmu_set_real_input_derivatives(ssx_fmu *fmu, const unsigned int *vr, size_t n,
                                       const int *order, const double *values);
int ssx_fmu_get_real_output_derivatives(ssx_fmu *fmu, const unsigned int *vr, size_t n,
                                        const int *order, double *values);
int ssx_fmu_reset(ssx_fmu *fmu);
int ssx_fmu_terminate(ssx_fmu *fmu);
/* 1 once a call returned fmi2Fatal: every later call is refused without reaching the FMU (FMI
 * 2.0 forbids them all, even fmi2FreeInstance); freeing abandons the instance. */
int ssx_fmu_is_dead(const ssx_fmu *fmu);
int ssx_fmu_is_instantiated(const ssx_fmu *fmu);
const char *ssx_fmu_last_message(const ssx_fmu *fmu); /* last message the FMU logged, "" if none */
/* The standard's name of the last call made on the FMU or refused ("fmi2DoStep"), "" before
 * any: the call a failure of ssx_fmu_initialize stopped at. */
const char *ssx_fmu_last_call(const ssx_fmu *fmu);
void ssx_fmu_get_counters(const ssx_fmu *fmu, ssx_fmu_counters *out);

/* ------------------------------------------------------------------------------------------
 * A system: components, ports, connections, indicators, event connections, the time loop and
 * the recorded history.
 * ------------------------------------------------------------------------------------------ */
typedef struct ssx_system ssx_system;

/* What kind of failure an ssx_error describes, so that a caller picks its exception without
 * reading the message. */
typedef enum {
    SSX_ERROR_NONE = 0,
    SSX_ERROR_CONFIG,     /* a call's arguments or the system's description were refused */
    SSX_ERROR_FMI,        /* an fmi2 call failed (fmi_status says how) */
    SSX_ERROR_CALLBACK,   /* a Python callback or the monitor reported failure (Python keeps the
                             exception) */
    SSX_ERROR_ZENO,       /* chattering (Zeno) or too many micro steps */
    SSX_ERROR_LOOP,       /* an algebraic loop did not converge */
    SSX_ERROR_TERMINATED, /* a component ended the run; initialize again before running */
    SSX_ERROR_NON_FINITE, /* an output or indicator is NaN or infinite */
    SSX_ERROR_SIMULATION  /* any other failure while running (out of memory, localization) */
} ssx_error_kind;

typedef struct {
    ssx_error_kind kind;
    int component;   /* index of the component involved, or -1 */
    int indicator;   /* index of the indicator involved, or -1 */
    int output;      /* index of the component's output involved, or -1 */
    double time;     /* simulation time of the failure */
    int fmi_status;  /* fmi2Status of the failing call, or -1 */
    char message[2048]; /* human-readable: what failed, where, and the FMU's last log message */
} ssx_error;

typedef struct {
    long macro_steps;            /* accepted macro steps (grid intervals and event-split pieces) */
    long do_step_calls;          /* doStep of any component, including localization trials */
    long state_saves;
    long state_restores;
    long events;                 /* event instants handled (one per (t, micro) with events) */
    long localization_iterations;
    long loop_iterations;        /* Newton/fixed-point iterations of algebraic loops */
    long loop_solves;
    long directional_derivatives; /* fmi2GetDirectionalDerivative calls for loop Jacobians */
    long own_events;             /* events components handled inside their own steps */
    /* error-controlled communication steps (ssx_set_step_control) */
    long accepted_steps;
    long rejected_steps;         /* retried after a restore with a smaller step */
    double smallest_step;        /* of the accepted steps; 0 before any */
    double largest_step;
    double largest_error;        /* the largest weighted coupling error of an accepted step */
    double error_sum;            /* of the accepted steps' errors: their mean is this / accepted */
    long steps_over_tolerance;   /* accepted at min_step (no shorter one allowed) with error > 1 */
    /* FMUs that could not give what the input order asks (ssx_coupling_fallbacks) */
    long input_order_fallbacks;       /* refused an input derivative order: a lower one since */
    long output_derivative_fallbacks; /* told non-finite output derivatives: estimated since */
    /* driven inputs the coupling-error step control cannot measure (String, Binary): left out
     * of its error */
    long unmeasured_inputs;
} ssx_statistics;

/* Who found an event: the master, by an indicator's crossing (located by rollback), or a
 * component inside its own step, at a time it knows without rollback. */
typedef enum {
    SSX_MASTER_EVENT = 0,  /* an indicator crossed */
    SSX_OWN_FMU_EVENT,     /* an FMI 3.0 FMU's event, handled in event mode after it returned */
    SSX_OWN_STATE_EVENT,   /* a Model Exchange FMU's event indicator crossed */
    SSX_OWN_TIME_EVENT,    /* a Model Exchange FMU's time event (nextEventTime) */
    SSX_OWN_STEP_EVENT,    /* a Model Exchange FMU asked for event mode after a completed step */
    SSX_OWN_CLOCK_TICK,    /* an FMI 3.0 FMU's periodic or triggered input clocks ticked */
    SSX_OWN_OUTPUT_CLOCK   /* an FMI 3.0 FMU's output clock ticked (fmi3GetClock) */
} ssx_own_event_kind;

typedef struct {
    double t;
    int micro;          /* superdense index of the handling round */
    int indicator;      /* which indicator fired; -1 for a component's own event */
    int component;      /* the component that owns the indicator or handled its own event */
    ssx_own_event_kind own; /* SSX_MASTER_EVENT, or the kind of the component's own event */
    /* SSX_OWN_OUTPUT_CLOCK: 1 + the index of the output clock that ticked; SSX_OWN_CLOCK_TICK
     * of a triggered clock: 1 + the triggered clock's index (ssx_fmi3_variables' lists);
     * 0 otherwise */
    int clock;
    int iterations;     /* localization iterations spent on the instant (0 for cascades) */
    int rollbacks;      /* restores spent on the instant */
    long do_steps;      /* doStep calls spent on the instant */
    /* Localization of a micro-0 event (n_trials == 0 and NAN values for cascades and for a
     * crossing at the very start): the initial bracket [t_left, t_right] (the macro piece that
     * crossed), this record's indicator at its ends, and its trials, read with
     * ssx_event_trial(first_trial + k) for k < n_trials. Every record of an instant lists the
     * instant's trials, so n_trials equals the iterations of the instant's first record. */
    double t_left, t_right;
    double value_left, value_right;
    size_t first_trial;
    int n_trials;
} ssx_event_record;

/* One localization trial: the whole system stepped from the bracket's left start to t. */
typedef struct {
    double t;
    double a, b;   /* the bracket after the trial (t is one of its ends) */
    double value;  /* the record's indicator at t */
} ssx_localization_trial;

/* Python-implemented behaviour. Every member may be NULL, which keeps the built-in behaviour of
 * an FMU component (for a Python component, do_step and evaluate_outputs are required).
 * Callbacks return 0 on success and -1 on failure (Python keeps the exception). The engine
 * calls none of them while a system is freed: Python drops its snapshots with its objects.
 * Python reads inputs and writes outputs through ssx_inputs()/ssx_outputs(). */
typedef struct {
    void *user;
    int (*initialize)(void *user, double t0);
    int (*do_step)(void *user, double t, double dt);       /* outputs valid afterwards */
    int (*evaluate_outputs)(void *user, double t);         /* zero-time: outputs from inputs */
    int (*snapshot)(void *user, int slot);                 /* save the state into slot */
    int (*restore)(void *user, int slot, double t);        /* the state of slot, now at time t */
    int (*handle_events)(void *user, const int *indicators, int n_indicators, double t);
    int (*record)(void *user, double t);                   /* a sample is being recorded at t */
} ssx_hooks;

/* A component asked to end the simulation: its fmi2DoStep returned fmi2Discard and
 * fmi2GetBooleanStatus(fmi2Terminated) answered true. The run ends cleanly at the last
 * communication point the whole system completed: the step's end when the FMU completed the
 * step (its fmi2LastSuccessfulTime reached the step's end), else the step's start. In the hybrid
 * algorithm nothing steps the component again: a request met while an event is being located
 * or probed ends the run at the last accepted instant. A later ssx_run fails until
 * ssx_initialize. */
typedef struct {
    int component;      /* the component that asked, or -1 while none has */
    double time;        /* the time it reached (fmi2LastSuccessfulTime) */
    char message[1024]; /* the FMU's last log message, "" if none */
} ssx_termination;

ssx_system *ssx_system_new(const char *name);
void ssx_system_free(ssx_system *sys); /* never frees the borrowed ssx_fmu objects */
const ssx_error *ssx_last_error(const ssx_system *sys);

int ssx_add_fmu_component(ssx_system *sys, const char *name, ssx_fmu *fmu, int can_get_set_state);
int ssx_add_python_component(ssx_system *sys, const char *name, int can_snapshot);
/* A Model Exchange FMU (loaded with interface SSX_MODEL_EXCHANGE, initialized by
 * ssx_fmu_initialize) that the engine integrates with CVODE between communication points:
 * n_states continuous states (ModelStructure/Derivatives; FMI 1.0: numberOfContinuousStates),
 * n_event_indicators (numberOfEventIndicators, FMI 3.0's ModelStructure/EventIndicator); an
 * FMI 3.0 instance that counts others fails its first step. The relative tolerance is the
 * one the instance was set up with (ssx_fmu_experiment's), else model_exchange_tolerance of
 * ssx_defaults; the absolute tolerances are it times the states' nominals. Its state, time and
 * step events are handled inside its steps at their own time and recorded as its own events
 * (ssx_own_event_kind); a request to terminate ends the run as for a Co-Simulation FMU. Its
 * snapshots hold the FMU state (fmi2GetFMUstate, when can_get_set_state) and the engine's copy
 * of the continuous states; ports are added as for any FMU component. */
int ssx_add_model_exchange_component(ssx_system *sys, const char *name, ssx_fmu *fmu,
                                     int can_get_set_state, int n_states,
                                     int n_event_indicators);
int ssx_set_hooks(ssx_system *sys, int component, const ssx_hooks *hooks);
/* A declarative event handler of an FMU component, run by the engine when an event reaches it
 * (a handle_events hook, when set, runs instead): the FMU starts again at the event time t from
 * its start values, as ssx_fmu_initialize does (a reset, else a new instance), set up with
 * `experiment` (its start time becomes t), `starts` written in initialization mode (copied
 * now; NULL: none), then each Real value reference vr[k] set to scale[k] * output[source[k]]
 * + offset[k] (the component's outputs at the event, source[k] an output index), then every
 * input holding a value; the outputs are read after. experiment NULL removes the handler. */
int ssx_set_restart_handler(ssx_system *sys, int component, const ssx_fmu_experiment *experiment,
                            const ssx_fmu_values *starts, const unsigned int *vr,
                            const int *source, const double *scale, const double *offset,
                            size_t n);

/* Ports. vr is the FMU value reference (ignored for Python components). start is written to
 * the FMU input at initialization when the input is unconnected; NaN (FMU components only)
 * means the user set no value: the input keeps the FMU's own, read by ssx_initialize. Return
 * the port's index. */
int ssx_add_output(ssx_system *sys, int component, ssx_value_type type, unsigned int vr);
int ssx_add_input(ssx_system *sys, int component, ssx_value_type type, unsigned int vr, double start);
/* The values of String and Binary ports (a String or Binary port connects only to one of its
 * type, unscaled): each distinct value has a number, kept until the system is freed.
 * ssx_text_number and ssx_bytes_number give the number of a text or of `size` bytes (added
 * when new), -1 when out of memory; ssx_text and ssx_bytes the value of a number (the
 * system's until it is freed, NUL-terminated; NULL for none); ssx_text_count how many
 * values there are. */
int ssx_text_number(ssx_system *sys, const char *text, double *number);
int ssx_bytes_number(ssx_system *sys, const void *data, size_t size, double *number);
const char *ssx_text(ssx_system *sys, double number);
const unsigned char *ssx_bytes(ssx_system *sys, double number, size_t *size);
size_t ssx_text_count(ssx_system *sys);
/* Before initializing a system again (its plan reused): every input's start value, the
 * components' inputs in order, n in all; each input holds its start again, as when added. */
int ssx_reset_inputs(ssx_system *sys, const double *starts, size_t n);
/* Members of an ensemble on a system initialized once, each run by one call. A member writes
 * n_columns values: column k is the start value of value reference vr[k] of type type[k]
 * (Real, Integer or Boolean) of FMU component component[k], and also of that component's
 * restart handler when restart[k] is nonzero. ssx_members_new returns NULL with the error
 * set. ssx_members_set_start gives each FMU component the experiment and start values it is
 * started from (copied; they hold every column of the component, whose value a member
 * replaces). ssx_run_member starts every FMU component again at t0 from its start values with
 * the member's `values` (n_columns) written into them (as ssx_fmu_enter_initialization does),
 * then ssx_initialize(t0) and ssx_run(t0, tf, dt): the history holds the member's samples.
 * 0, or -1 with the error set. ssx_members_free does not touch the system. */
typedef struct ssx_members ssx_members;
ssx_members *ssx_members_new(ssx_system *sys, size_t n_columns, const int *component,
                             const int *type, const unsigned int *vr, const int *restart);
int ssx_members_set_start(ssx_members *members, int component,
                          const ssx_fmu_experiment *experiment, const ssx_fmu_values *starts);
int ssx_run_member(ssx_members *members, const double *values, double t0, double tf, double dt);
/* n members one after another, member k with the n_columns values at values + k * n_columns,
 * each run as ssx_run_member and its samples kept: ssx_members_samples gives the members run
 * by the last call (all n, or those before the one that failed: -1 with the error set) as
 * rows of `width` doubles, the time and then every component's outputs in component order,
 * one row per sample, members one after another (member k's rows bounds[k] to bounds[k + 1]),
 * and each row's micro step; valid until the next ssx_run_members or ssx_members_free. */
int ssx_run_members(ssx_members *members, size_t n, const double *values, double t0, double tf,
                    double dt);
size_t ssx_members_samples(const ssx_members *members, const double **rows, const int **micro,
                           const size_t **bounds, size_t *width);
void ssx_members_free(ssx_members *members);
/* A component's n_outputs (n_inputs) current values. ssx_initialize moves them, with every
 * other component's, into one block in schedule order when the structure changed (adding a
 * port moves the component's out again): take the address again after ssx_initialize. */
double *ssx_outputs(ssx_system *sys, int component);
double *ssx_inputs(ssx_system *sys, int component);

/* dst_input = scale * src_output + offset, applied in C (units resolved by Python). One driver
 * per input: a second connection to the same input fails. */
int ssx_connect(ssx_system *sys, int src_component, int src_output, int dst_component,
                int dst_input, double scale, double offset);

/* Built-in behaviour, callable from Python overrides (the super() of the hooks). */
int ssx_component_do_step(ssx_system *sys, int component, double t, double dt);
int ssx_component_write_inputs(ssx_system *sys, int component);
int ssx_component_read_outputs(ssx_system *sys, int component);
int ssx_component_snapshot(ssx_system *sys, int component, int slot);
int ssx_component_restore(ssx_system *sys, int component, int slot, double t);

/* Event indicators. direction: -1 falling, +1 rising, 0 both. An indicator on an output is
 * evaluated in C; a callback indicator calls Python (value written to *value). */
int ssx_add_indicator_output(ssx_system *sys, int component, int output, int direction);
int ssx_add_indicator_callback(ssx_system *sys, int component,
                               int (*evaluate)(void *user, double t, double *value), void *user,
                               int direction);
/* Indicator `indicator` (on an output of an FMU component) has its time derivative in the FMU's
 * Real variable `vr` (the variable a modelDescription declares its derivative): localization
 * reads it at the bracket ends and at each trial, and aims from the slope (cubic Hermite, then
 * Newton) instead of from values alone. Other kinds of component refuse it. */
int ssx_set_indicator_slope(ssx_system *sys, int indicator, unsigned int vr);
/* Where events come from: an event indicator the master locates (index: the indicator's), or
 * the events a component handles inside its own steps (index: the component's; an FMI 3.0
 * FMU's events, a Model Exchange FMU's state, time and step events). */
typedef enum {
    SSX_SOURCE_INDICATOR = 0,
    SSX_SOURCE_OWN_EVENTS = 1,
    SSX_SOURCE_OUTPUT_CLOCK = 2 /* index: the number ssx_add_output_clock_source gave */
} ssx_event_source_kind;
/* The listener's handle_events hook (else its built-in reaction, an FMU's restart handler)
 * runs when the source fires; it receives the sources that fired, an indicator as its index,
 * a component's own events as -1 - component. An indicator's listeners run at the located
 * event time, components in index order, before the instant's next sample. Own events' are
 * called when the master accepts the step that holds them, in time order (component order at
 * one time) and before indicators' at the same communication point: the hook receives the
 * event's own time t_e, while the system stands at the step's end (ssx_time says so; a
 * built-in reaction runs there, at that time); what a listener changes shows from that communication point's sample
 * on. Subscribing twice is one subscription. */
int ssx_subscribe(ssx_system *sys, ssx_event_source_kind kind, int index, int listener_component);
/* An output clock of an FMI 3.0 Co-Simulation component (clock: its index among
 * ssx_fmi3_variables' output clocks) as an event source: returns its number s (the same for the
 * same clock), or -1. Its ticks reach listeners as own events do (when the master accepts the
 * step that holds them, the hook receiving the tick's time and the source as
 * -1 - n_components - s, n_components counted when the system runs). */
int ssx_add_output_clock_source(ssx_system *sys, int component, int clock);
/* A clock connection: when the source fires (SSX_SOURCE_INDICATOR: at the located event time;
 * SSX_SOURCE_OUTPUT_CLOCK: where the master accepts the step that holds the tick, the
 * communication point after it or a located event's instant), the triggered input clock
 * `clock` (its index among ssx_fmi3_variables' triggered clocks) of the FMI 3.0 Co-Simulation
 * component `listener_component` ticks there: its inputs take their drivers' outputs, the FMU
 * enters Event Mode, the clock is set (fmi3SetClock), its discrete states are updated, it
 * enters Step Mode and its outputs are read; the tick is recorded as its own event
 * (SSX_OWN_CLOCK_TICK, record.clock 1 + the clock). The clocks a firing ticks tick before its
 * listeners' hooks run, in the order they were connected. Connecting twice is one
 * connection. */
int ssx_connect_clock(ssx_system *sys, ssx_event_source_kind kind, int index,
                      int listener_component, int clock);
/* ssx_subscribe(sys, SSX_SOURCE_INDICATOR, indicator, listener_component). */
int ssx_add_event_connection(ssx_system *sys, int indicator, int listener_component);

/* Scheduling. order lists every component once, as n_groups consecutive groups of
 * group_sizes[g] members; group_is_loop[g] marks an algebraic loop (solved at every
 * communication point over the real inputs that the group's members drive). Without a call,
 * components run in the order they were added, with no loops. */
int ssx_set_schedule(ssx_system *sys, const int *order, const int *group_sizes,
                     const int *group_is_loop, int n_groups);
int ssx_set_coupling(ssx_system *sys, ssx_coupling coupling);
/* Steps FMU components on `threads` threads (1 .. SSX_MAX_THREADS): the calling thread and
 * threads - 1 workers, started at the next ssx_initialize and kept until the system is freed.
 * Under Jacobi every component of a step may run on any of them; under Gauss-Seidel those of
 * consecutive groups none of which feeds a later one of them in the same step, and the members
 * of a loop. Python-backed components, table sources, components marked with
 * ssx_set_calling_thread_only and components sharing one ssx_fmu step on the calling thread;
 * so do the monitor, the recording and the event handling, and the steps whose FMUs together
 * took less than a hand-off to the workers costs (about 20 us). Each FMU steps on its own
 * instance from inputs set before the step, so the results, the statistics and the first error
 * (in schedule order) are those of one thread. */
enum { SSX_MAX_THREADS = 256 };
int ssx_set_threads(ssx_system *sys, int threads);
/* The component steps on the thread that calls ssx_run (on: nonzero): for an FMU whose
 * modelDescription declares canBeInstantiatedOnlyOncePerProcess (its binary may keep state
 * that expects one thread). Off by default. */
int ssx_set_calling_thread_only(ssx_system *sys, int component, int only);
int ssx_set_loop_options(ssx_system *sys, double tolerance, int max_iterations, double damping);
/* The FMU of an FMU component provides fmi2GetDirectionalDerivative (its modelDescription says
 * providesDirectionalDerivative="true"); off until set. */
int ssx_set_directional_derivatives(ssx_system *sys, int component, int provided);
/* How Newton builds a loop's Jacobian. SSX_JACOBIAN_AUTO (the default): the columns of the
 * inputs of FMU components that provide directional derivatives (and have no evaluate_outputs
 * hook) come from fmi2GetDirectionalDerivative, the others from finite differences.
 * SSX_JACOBIAN_FINITE_DIFFERENCES: every column from finite differences. */
int ssx_set_loop_jacobian(ssx_system *sys, ssx_loop_jacobian jacobian);
/* Higher-order inputs. Order 0 (the default) holds every input over a communication step.
 * Order 1 or 2 passes the first (and second) time derivative of each connected Real input to
 * the FMUs that declare canInterpolateInputs (fmi2SetRealInputDerivatives): interpolated
 * between a Gauss-Seidel driver's outputs at t and t + h when it steps first, else extrapolated
 * from t with the driver's output derivatives where it declares maxOutputDerivativeOrder >= 1,
 * or from the outputs at the last communication points. Inputs of FMUs that cannot
 * interpolate (unless ssx_set_extrapolate_held_inputs), and of algebraic loop members, are
 * held. Applies at the next ssx_initialize. */
enum { SSX_MAX_INPUT_ORDER = 2 };
int ssx_set_input_order(ssx_system *sys, int order);
/* With input order 1 or 2, the inputs an FMU holds over a step (it cannot interpolate) may be
 * extrapolated too: each is set, for the whole step, to the mean over the step of the polynomial
 * the interpolating FMUs follow (the value at t + h/2 for order 1). A held input then errs by
 * O(h^2) in its integral over the step instead of O(h), and the coupling is second order in h
 * (order 2 shrinks the error further, the order stays 2). Off by default: an extrapolation may
 * overshoot where a signal turns sharply. Applies at the next ssx_initialize. */
int ssx_set_extrapolate_held_inputs(ssx_system *sys, int extrapolate);
/* What an FMU component's modelDescription declares: canInterpolateInputs and
 * maxOutputDerivativeOrder; both off until set. */
int ssx_set_interpolation(ssx_system *sys, int component, int can_interpolate_inputs,
                          int max_output_derivative_order);
/* Error-controlled communication steps: the steps inside each interval of the run's grid (dt)
 * are chosen by the coupling error, the largest over the connections of
 * |driver output at t + h - input value reached at t + h| / (atol + rtol |output|).
 * rollback: a step whose error exceeds 1 is taken again, from a restored state, with a smaller
 * step (every component must save and restore its state); without rollback the step is kept
 * and only the next ones shrink (non-iterative, as libcosim's ECCO). The next step is the
 * last times safety * error^(-1/(order + 1)), within [min_step, max_step] (max_step 0: no bound
 * but the grid) and between min_change and max_change times the last; initial_step <= 0 starts
 * with a tenth of the grid step times max(rtol, atol)^(1/(order + 1)). Events are still located
 * to tol_time inside the steps. Applies at the next ssx_initialize.
 *
 * energy = 1 measures instead the energy residual of the power bonds (ssx_set_power_bonds), as
 * libcosim's ECCO algorithm does (Sadjina et al.): per bond, the power each side computes, its
 * input times its output, differs by dP; the error is the root mean square over the bonds of
 * |dP| h / (atol + rtol max(|P|) h), and a PI controller chooses the next step: the last times
 * safety * error^-(integral_gain + proportional_gain) * previous error^proportional_gain. */
typedef struct {
    int enabled;
    int rollback;
    double rtol;
    double atol;
    double min_step;
    double max_step;
    double initial_step;
    double safety;
    double min_change; /* 0 < min_change < 1 < max_change */
    double max_change;
    int energy;
    double proportional_gain; /* >= 0, energy only */
    double integral_gain;     /* > 0, energy only */
    int strict; /* a step at min_step still over the tolerance fails the run (else counted) */
} ssx_step_control;
int ssx_set_step_control(ssx_system *sys, const ssx_step_control *control);
/* What the coupling does instead where an FMU cannot give what the input order asks, per
 * component, since ssx_initialize: an FMU whose fmi2SetRealInputDerivatives
 * (fmiSetRealInputDerivatives) returns Discard or Error for an order gets the next lower one
 * from then on (at 0 its inputs are held over each step); one whose output derivatives come back
 * NaN or infinite has them estimated from its outputs at the communication points instead, from
 * then on. Each counts once in the statistics. */
typedef struct {
    int component;
    int input_order;                /* the input derivative order it is given now */
    double input_order_time;        /* when it refused one; NaN: never */
    double output_derivatives_time; /* when its output derivatives were non-finite; NaN: never */
} ssx_coupling_fallback;
/* How many components fell back; the first `max` into out. */
int ssx_coupling_fallbacks(const ssx_system *sys, ssx_coupling_fallback *out, int max);
/* The power bonds of the energy error: bond k joins input ends[4k + 1] of component ends[4k]
 * (a force or torque, say) and input ends[4k + 3] of component ends[4k + 2] (the velocity), each
 * driven by a Real output of the other component. Replaces the bonds set before; checked at
 * ssx_initialize. */
int ssx_set_power_bonds(ssx_system *sys, int n_bonds, const int *ends);

/* Hybrid mode is active whenever an indicator exists. Two firings of one indicator closer than
 * zeno_min_interval are chattering (a Zeno error). zeno_min_interval <= 0: closer than ten times
 * tol_time, or closer than a tenth of the communication step once the intervals stop shrinking
 * (each at most 0.9 times the one before goes on: the way to an accumulation point). */
int ssx_set_hybrid_options(ssx_system *sys, double tol_time, double tol_value, int max_iterations,
                           int max_microsteps, int record_internal_steps, ssx_locator locator,
                           double zeno_min_interval);

const ssx_termination *ssx_get_termination(const ssx_system *sys);
/* Off by default: a NaN or infinite output that feeds something (a connected input, an event
 * indicator) stops the run with an error naming the component, the output and the time (the
 * samples before it are kept); one that feeds nothing is recorded, and the run goes on. On:
 * such values are recorded wherever they go. An event indicator must be finite either way. */
int ssx_set_allow_non_finite(ssx_system *sys, int allow);
/* The outputs that were NaN or infinite since ssx_initialize though they feed nothing: how
 * many, and the first `max` of them (component, output, the first time one was seen) in
 * components, outputs and times. */
int ssx_non_finite_outputs(const ssx_system *sys, int *components, int *outputs, double *times,
                           int max);

/* initialize: the components are initialized, each FMU by ssx_fmu_initialize or left in
 * initialization mode by ssx_fmu_enter_initialization. In schedule order, each component's
 * driven inputs take its drivers' outputs at t0 (converted by the connections); an FMU still in
 * initialization mode is given them there and then leaves it (an algebraic loop's members are
 * iterated there first where their standard lets outputs be read, FMI 2.0 and 3.0), so that
 * what it computes on leaving sees them. Then its outputs are read, loops solved, the history
 * cleared and started with the sample at t0 and the indicators evaluated. */
int ssx_initialize(ssx_system *sys, double t0);
/* run from the current time t0 to tf on the grid t0 + k*dt (the last point is exactly tf),
 * plus event instants. Recorded samples stay readable after a failure. */
int ssx_run(ssx_system *sys, double t0, double tf, double dt);
double ssx_time(const ssx_system *sys);

/* The execution: a run taken a stretch at a time (what an exported FMU's doStep does).
 * ssx_step_until advances from the current time with communication step dt, exactly as
 * ssx_run does (the algorithm, step control, loops, recording), and returns at t_stop, or right
 * after the first event instant an indicator made was located and handled (then out->event is
 * set and out->time is the instant, at most t_stop); calling it again goes on from there. The
 * grid is t0 + k*dt from the time of ssx_initialize (or of the last ssx_run's t0); another dt
 * starts a new grid at the current time. A t_stop off the grid ends the step that would cross
 * it at t_stop (a remainder below 1e-9 steps joins it), as ssx_run's last step ends at tf; the
 * next call completes the step to its grid point. Each call is one run for the recording and
 * the observers (its samples, its run_end). ssx_run is a loop over the same steps. */
typedef struct {
    double time;   /* where the system is now (ssx_time) */
    int event;     /* it stopped right after an event instant (time) */
    int own_event; /* that instant was a member's own event (ssx_set_stop_at_own_events) */
    long events;   /* event instants handled since ssx_initialize (statistics.events) */
    int status;    /* the call's return: 0, or -1 (ssx_last_error says why) */
    int terminated; /* a component asked to end the simulation (ssx_get_termination) */
} ssx_step_outcome;
int ssx_step_until(ssx_system *sys, double t_stop, double dt, ssx_step_outcome *out);
/* Whether ssx_step_until also stops right after a member's own event (a Model Exchange member's
 * state or time event, an FMI 3.0 member's event, a clock's tick), taken at the next
 * ssx_initialize; off by default. On, and where every component can save and restore its
 * state, the system steps as one with indicators does: a step in which a member reported an
 * event is taken again from its start to end at that event's time, so the member handles it
 * at the step's end and the call returns there (out->event and out->own_event set). Those
 * steps end where a run's would not, so ssx_run is not made to stop there: an exported FMI 3.0
 * FMU asks for it when its importer allows early return. Where a component cannot roll back,
 * own events do not stop the call. */
int ssx_set_stop_at_own_events(ssx_system *sys, int stop);
/* The whole system's state by handle, between calls (after ssx_initialize): every component's
 * state (an FMU's through fmi2GetFMUstate / fmi3GetFMUState, a Model Exchange component's also
 * the engine's copy of its continuous states; a table holds none), every port value, the
 * indicators' sides and the hybrid algorithm's event state, the step control's next step, the
 * input motion, the grid the execution is on and the statistics. ssx_state_save returns NULL
 * with the error set when a component cannot save its state (its FMU does not declare
 * canGetAndSetFMUstate; a Python component or hook). ssx_state_restore puts the system back
 * (observers are told: state_restored at the state's time): stepping on repeats what followed
 * the save, as far as the FMUs step the same from a set state (an integrator that starts afresh
 * from a set state differs within its tolerance). The recorded history and event records are
 * not rewound: what was recorded stays, samples after a restore are appended. A state belongs to
 * the system and to the FMU instances it was saved from: free it before them. Serialized, a
 * state is bytes (freed with ssx_state_bytes_free) that begin with a magic, a format version
 * and a digest of the system's layout (components, ports, indicators); ssx_state_deserialize
 * refuses bytes of another layout naming what differs, and makes a state of this system that
 * ssx_state_restore puts back (FMU states through fmi2DeSerializeFMUstate). String and Binary
 * port values are numbers of the system's own text table: a system with such ports cannot
 * serialize its state. */
typedef struct ssx_system_state ssx_system_state;
ssx_system_state *ssx_state_save(ssx_system *sys);
int ssx_state_restore(ssx_system *sys, const ssx_system_state *state);
void ssx_state_free(ssx_system_state *state);
int ssx_state_serialize(ssx_system *sys, const ssx_system_state *state, unsigned char **bytes,
                        size_t *size);
ssx_system_state *ssx_state_deserialize(ssx_system *sys, const unsigned char *bytes,
                                        size_t size);
/* Frees the bytes ssx_state_serialize handed back (a caller that shares no C library with
 * the engine, such as Python, cannot call the engine's free itself); NULL does nothing. */
void ssx_state_bytes_free(unsigned char *bytes);

/* A watch over ssx_run: between macro steps, about every SSX_MONITOR_INTERVAL_MS of wall
 * time, monitor(user, t) is called with the time reached; nonzero stops the run, which then
 * fails at t with kind SSX_ERROR_CALLBACK (the monitor keeps its reason). The clock is read only
 * every few steps, as many as take about a tenth of the interval. Python runs its signal
 * handlers there, so Ctrl-C and timeouts stop a run. NULL removes the monitor. */
enum { SSX_MONITOR_INTERVAL_MS = 50 };
int ssx_set_monitor(ssx_system *sys, int (*monitor)(void *user, double t), void *user);

/* History: one shared time axis; per component a row-major matrix with one row per sample and
 * one column per output. Pointers are valid until the next call that records, unless the
 * history is retained. */
size_t ssx_history_length(const ssx_system *sys);
const double *ssx_history_time(const ssx_system *sys);
const int *ssx_history_micro(const ssx_system *sys); /* -1: a localization trial
                                                       (record_internal_steps) */
const double *ssx_history_values(const ssx_system *sys, int component);
size_t ssx_history_bytes(const ssx_system *sys); /* bytes allocated for the history */
/* Decimation: the history keeps every grid_steps-th communication point (counted from t0),
 * the last point of each ssx_run and every event instant and trial. 1, the default, keeps
 * every sample. Takes effect at the next ssx_initialize. */
int ssx_set_output_interval(ssx_system *sys, int grid_steps);
/* Decimation per run (FMPy's output_interval): every following ssx_run keeps every
 * grid_steps-th communication point counted from its own start (the 0th), its last point and
 * every event instant and trial, whatever ssx_set_output_interval says; 0, the default, returns
 * to the system's interval. */
int ssx_set_run_output_interval(ssx_system *sys, int grid_steps);
/* Observers: code of the user's that the run reports to as it goes (libcosim's observers), a
 * file written while the run goes on, say. An observer sees the samples the history keeps (the
 * same decimation), in the same order, and reads their values through ssx_outputs() during
 * step_complete. Every member may be NULL; each returns 0, or -1 to stop the run (kind
 * SSX_ERROR_CALLBACK; Python keeps the exception). The engine calls none of them while a
 * system is freed.
 *   start           ssx_initialize, before the sample at t0
 *   step_complete   a sample: the communication point t (micro 0), an event instant before
 *                   and after handling (micro 0, 1, ...), a trial (micro -1, only with
 *                   record_internal_steps)
 *   state_restored  the system went back to its state at t: later samples were trials
 *   event           an event was handled; its record is complete
 *   run_end         ssx_run returns, whatever its status (its result is ignored) */
typedef struct {
    int (*start)(void *user, double t0);
    int (*step_complete)(void *user, double t, int micro);
    int (*state_restored)(void *user, double t);
    int (*event)(void *user, const ssx_event_record *record);
    int (*run_end)(void *user);
} ssx_observer_callbacks;
/* Adds an observer (callbacks copied) after those added before. Added after ssx_initialize, it
 * is started by the next ssx_run and sees the samples from there. Returns its id (> 0) for
 * ssx_remove_observer, or -1 with the error set. Neither adding nor removing may happen during
 * a run (from a callback). */
int ssx_add_observer(ssx_system *sys, const ssx_observer_callbacks *callbacks, void *user);
/* A block observer: the samples an observer sees, gathered into blocks of up to `rows` rows
 * (times, micro steps, and every component's outputs in component order, row-major: n_rows x
 * n_columns) and handed to `write` when a block is full, at the last point of each run, and
 * after a failed run with what came before the failure. The arrays are valid during the call.
 * `write` returns 0 (written), > 0 (written; the run stops, failed) or < 0 (not written; the
 * run stops, failed, and the rows are handed again as it ends). How a file is written while the
 * run goes on in bounded memory. Returns its id, or -1. */
typedef int (*ssx_block_writer)(void *user, const double *t, const int *micro,
                                const double *values, size_t n_rows, size_t n_columns);
int ssx_add_block_observer(ssx_system *sys, size_t rows, ssx_block_writer write, void *user);
/* Removes the observer of that id; its callbacks are never called again. 0, or -1. */
int ssx_remove_observer(ssx_system *sys, int observer);
/* keep 0: the history keeps no more samples, for a run that only observers keep, larger than
 * memory would hold: from the next ssx_run on (its samples so far are dropped then). keep 1,
 * the default: the history keeps the samples again from the next ssx_initialize. */
int ssx_set_history(ssx_system *sys, int keep);

/* A reference to the buffers the history accessors return now: until it is released, their
 * first ssx_history_length() samples are never written, moved or freed, whatever the system
 * does (record, initialize again, ssx_system_free). This is how Python hands out numpy arrays
 * without a copy. NULL before ssx_initialize. Release from any thread, once per retain. */
typedef struct ssx_history_block ssx_history_block;
ssx_history_block *ssx_history_retain(ssx_system *sys);
void ssx_history_release(ssx_history_block *block);
/* A component's samples in a retained block (ssx_history_values at the time of the retain):
 * read later, after the system is gone, as long as the block is held. */
const double *ssx_history_block_values(const ssx_history_block *block, int component);

size_t ssx_event_count(const ssx_system *sys);
int ssx_event_get(const ssx_system *sys, size_t index, ssx_event_record *out);
size_t ssx_event_trial_count(const ssx_system *sys);
int ssx_event_trial(const ssx_system *sys, size_t index, ssx_localization_trial *out);
/* Records (trials) first .. first + n - 1, or as many of them as there are, copied into out in
 * one call; returns how many were copied. */
size_t ssx_events_copy(const ssx_system *sys, size_t first, size_t n, ssx_event_record *out);
size_t ssx_event_trials_copy(const ssx_system *sys, size_t first, size_t n,
                             ssx_localization_trial *out);
void ssx_get_statistics(const ssx_system *sys, ssx_statistics *out);
/* What a caller reads after each run, in one call: each field is what its accessor gives now.
 * For a caller that pays per call (Python through cffi) a short run's reading is then one
 * crossing, not eight. `history` is a reference as ssx_history_retain gives it (NULL when
 * nothing is recorded): the caller releases it with ssx_history_release. */
typedef struct {
    double time;                        /* ssx_time */
    size_t n_events;                    /* ssx_event_count */
    const ssx_termination *termination; /* ssx_get_termination */
    ssx_statistics statistics;          /* ssx_get_statistics */
    size_t history_length;              /* ssx_history_length */
    ssx_history_block *history;         /* ssx_history_retain, when history_length > 0 */
    const double *history_time;         /* ssx_history_time */
    const int *history_micro;           /* ssx_history_micro */
} ssx_run_outcome;
void ssx_get_run_outcome(ssx_system *sys, ssx_run_outcome *out);

/* ------------------------------------------------------------------------------------------
 * Isolation: an FMU whose binary runs in a process of its own.
 * ------------------------------------------------------------------------------------------ */
/* An FMU loaded with a host_path runs its binary in a host process and every fmi2 call is
 * forwarded to it, FMU states included. A crash, abort or exit inside the FMU fails the call
 * with fmi2Fatal and the FMU's last message says how the process ended (the signal); this
 * process goes on. With step_timeout > 0, a call that has not returned after step_timeout
 * seconds kills the host and fails the same way. The next ssx_fmu_instantiate starts a new
 * host; ssx_fmu_free ends it and waits for it. */

/* ------------------------------------------------------------------------------------------
 * Table sources: a component whose outputs are the columns of a time table, evaluated in C
 * with the rules of FMPy's input signals (first row before the table, last row after it,
 * linear interpolation for real columns unless held, hold of the row on the left for integer,
 * boolean and held columns, the value on the right of a repeated time stamp once the run has
 * started). A table has no state, so it rolls back with any system.
 * ------------------------------------------------------------------------------------------ */
/* time: n_rows non-decreasing finite times (copied). Returns the component's index. */
int ssx_add_table_component(ssx_system *sys, const char *name, const double *time, size_t n_rows);
/* One output per column, in order: values holds n_rows finite numbers (copied). hold != 0
 * holds a real column between rows. Returns the output's index. */
int ssx_add_table_column(ssx_system *sys, int component, ssx_value_type type, int hold,
                         const double *values);
/* The table's value of every column at t into values (one per output); after_event != 0 takes
 * the value on the right of a jump at t. Changes nothing. */
int ssx_table_values(ssx_system *sys, int component, double t, int after_event, double *values);

/* ------------------------------------------------------------------------------------------
 * FMI 3.0 Scheduled Execution: a component whose FMU (loaded with SSX_SCHEDULED_EXECUTION and
 * started with ssx_fmu_enter_initialization) has no step: each step from t to t + h runs, in
 * time order, the partitions of the input clocks that tick in [t, t + h) (a tick within the
 * grid's rounding of t + h is the next step's), ticks at one instant by priority (lowest first),
 * then value reference, then the order they were planned in. The inputs are written before
 * each partition, the outputs its clock moves read after it; each output clock that ticked is
 * an own event (SSX_OWN_OUTPUT_CLOCK, record.clock 1 + its index among the FMU's output clocks,
 * a source for ssx_add_output_clock_source). Every tick is logged. It cannot roll back.
 *
 * Its clocks, after its ports: each input clock of the FMU and each output clock in the order
 * of the load spec's output clocks (and the countdown clocks in the order of its countdown
 * clocks). A periodic clock ticks at t0 + shift and every interval after it (interval NaN: the
 * FMU's, asked after initialization, and after each tick when interval_tunable); a triggered
 * one at the times set; a countdown one when the FMU announces it. priority < 0: none (after
 * every clock with one). Returns the clock's index. */
typedef enum {
    SSX_SCHEDULED_PERIODIC = 0,
    SSX_SCHEDULED_TRIGGERED = 1,
    SSX_SCHEDULED_COUNTDOWN = 2,
    SSX_SCHEDULED_OUTPUT = 3
} ssx_scheduled_clock_kind;
int ssx_add_scheduled_component(ssx_system *sys, const char *name, ssx_fmu *fmu);
int ssx_add_scheduled_clock(ssx_system *sys, int component, ssx_scheduled_clock_kind kind,
                            unsigned int vr, long long priority, double interval, double shift,
                            int interval_tunable);
/* The times (finite, not decreasing) a triggered clock ticks at, replacing earlier ones. */
int ssx_set_scheduled_clock_times(ssx_system *sys, int component, int clock, const double *times,
                                  size_t n);
/* Output `output` of the component is moved by the ticks of input clock `clock`: read after
 * each and logged with it. */
int ssx_add_scheduled_clock_output(ssx_system *sys, int component, int clock, int output);
/* The log since ssx_initialize: how many ticks (and in *n_values how many values they moved),
 * then the ticks: tick k at time[k] of clock clock[k], having moved outputs output[i] to
 * value[i] for i in first_value[k] .. first_value[k + 1] (n ticks + 1 entries). An output
 * clock's tick follows the partition's that ticked it and moves nothing. */
size_t ssx_scheduled_tick_count(ssx_system *sys, int component, size_t *n_values);
int ssx_scheduled_ticks(ssx_system *sys, int component, double *time, int *clock,
                        size_t *first_value, int *output, double *value);

/* ------------------------------------------------------------------------------------------
 * Plans: a system as plain data, in the text format of docs/reference/plan-format.md, built
 * into a system with no Python (an exported FMU's binary does so).
 * ------------------------------------------------------------------------------------------ */
typedef struct ssx_plan ssx_plan;
/* Reads text[0..size). NULL on failure, with the reason in error (the line, the record, the
 * field). Bounded: a text over 256 MiB, a line over 64 MiB, a string over 16 MiB, a list over
 * 2^26 items and over 2^20 components are refused. */
ssx_plan *ssx_plan_read(const char *text, size_t size, char *error, size_t error_size);
/* The plan as text (NUL-terminated, its length without the NUL in *size), freed with
 * ssx_plan_text_free; NULL when out of memory. Reading it gives the plan back, and writing
 * that plan the same text. */
char *ssx_plan_write(const ssx_plan *plan, size_t *size);
void ssx_plan_text_free(char *text);
void ssx_plan_free(ssx_plan *plan);
/* A system made by the plan's records, in order. given[k] (k < n_given, non-NULL): the loaded
 * FMU of the plan's k-th component, borrowed, which its caller initializes; every other FMU is
 * loaded here from its unpacked folder (relative to base_folder unless absolute) and freed
 * with the system. Python components and callback indicators are placeholders: their hooks
 * (ssx_set_hooks) and functions (ssx_set_indicator_callback) are the caller's to attach. NULL
 * on failure, with the reason in error (the record's line). */
ssx_system *ssx_plan_build(const ssx_plan *plan, const char *base_folder, ssx_fmu *const *given,
                           size_t n_given, char *error, size_t error_size);
/* Initializes a system the plan built, at t0: every FMU the build loaded is made ready (as
 * ssx_fmu_enter_initialization: its fmu_experiment, its start records, then its unconnected
 * inputs' start values that are not NaN), then ssx_initialize(sys, t0). FMUs the caller gave
 * must be in initialization mode (or initialized) already. 0, or -1 with the error set. */
int ssx_plan_initialize(ssx_system *sys, const ssx_plan *plan, double t0);
/* What an exporter maps its variables to: the components (in plan order), their names, and
 * their outputs (is_input 0) or inputs (1) by index, with type and value reference. The
 * experiment record's values, 0 when it has one, -1 when not. */
int ssx_plan_component_count(const ssx_plan *plan);
const char *ssx_plan_component_name(const ssx_plan *plan, int component);
int ssx_plan_port_count(const ssx_plan *plan, int component, int is_input);
int ssx_plan_port(const ssx_plan *plan, int component, int is_input, int port,
                  ssx_value_type *type, unsigned int *vr);
int ssx_plan_experiment(const ssx_plan *plan, double *start, double *stop, double *step);
/* The function of callback indicator `indicator` (one a plan made, say). */
int ssx_set_indicator_callback(ssx_system *sys, int indicator,
                               int (*evaluate)(void *user, double t, double *value), void *user);

/* ------------------------------------------------------------------------------------------
 * modelDescription.xml (FMI 2.0 and 1.0), read into compact arrays: one pass over the text,
 * no tree, no object per variable. The reader is a small XML tokenizer for what a modelDescription
 * uses (elements, attributes in either quote, the five predefined entities, character
 * references, comments, processing instructions, CDATA skipped; UTF-8 only, no DOCTYPE).
 * Elements count only at their place in the schema (fmiModelDescription/CoSimulation,
 * .../ModelVariables/ScalarVariable/Real, .../ModelStructure/Outputs/Unknown); annotations
 * are ignored. It refuses what would make syssimx exchange wrong data: two variables of one
 * name, a value reference outside 0..2**32-1, a start that is not a value of the variable's
 * type, an undefined declaredType, a causality/variability pair FMI 2.0 forbids, a
 * ModelStructure index that names no variable. FMI 1.0 is read in FMI 2.0's words: a
 * parameter is causality parameter and variability fixed, internal and none are local, a
 * negated alias is local (no port), initial is absent, each output depends on everything, and
 * the Capabilities of Implementation/CoSimulation_* are kept (their presence: Co-Simulation).
 * ------------------------------------------------------------------------------------------ */
/* The words of FMI 2.0 a variable is described by; SSX_MD_NONE: absent. */
typedef enum {
    SSX_MD_NONE = 0,
    SSX_MD_PARAMETER, SSX_MD_CALCULATED_PARAMETER, SSX_MD_INPUT, SSX_MD_OUTPUT, SSX_MD_LOCAL,
    SSX_MD_INDEPENDENT,                                                      /* causality */
    SSX_MD_CONSTANT, SSX_MD_FIXED, SSX_MD_TUNABLE, SSX_MD_DISCRETE, SSX_MD_CONTINUOUS,
                                                                             /* variability */
    SSX_MD_EXACT, SSX_MD_APPROX, SSX_MD_CALCULATED,                          /* initial */
    SSX_MD_REAL, SSX_MD_INTEGER, SSX_MD_BOOLEAN, SSX_MD_STRING, SSX_MD_ENUMERATION, /* type */
    SSX_MD_WORD_COUNT
} ssx_md_word;

/* Why reading stopped. The fields of ssx_md_error each problem fills are named after it. */
typedef enum {
    SSX_MD_OK = 0,
    SSX_MD_NOT_XML,                /* line, detail */
    SSX_MD_NOT_FMI2,               /* neither 2.0 nor 1.0; text: the fmiVersion (NULL: none) */
    SSX_MD_NO_FMI_ROOT,            /* the root element is not an fmiModelDescription */
    SSX_MD_TYPE_WITHOUT_ELEMENT,   /* subject: the SimpleType's name (NULL when absent) */
    SSX_MD_VARIABLE_WITHOUT_NAME,  /* text: its valueReference (NULL when absent) */
    SSX_MD_NO_TYPE_ELEMENT,        /* subject */
    SSX_MD_VALUE_REFERENCE_NOT_INTEGER, /* subject, text (NULL when absent) */
    SSX_MD_VALUE_REFERENCE_OUT_OF_RANGE, /* subject, text */
    SSX_MD_BAD_START,              /* subject, text, word: the variable's type */
    SSX_MD_UNDEFINED_TYPE,         /* subject, text: the declaredType */
    SSX_MD_BAD_COMBINATION,        /* subject, text: causality, other: variability */
    SSX_MD_BAD_INITIAL,            /* subject, text: initial */
    SSX_MD_BAD_INDEX,              /* text: the index (NULL when absent), count */
    SSX_MD_TOO_LARGE,              /* the text is 4 GiB or more */
    SSX_MD_NO_MEMORY
} ssx_md_problem;

typedef struct {
    ssx_md_problem problem;
    size_t line;       /* where the element that failed starts (1: the first line) */
    char *subject;     /* copies of the texts involved, NULL when absent */
    char *text;
    char *other;
    int word;
    size_t count;      /* variables read so far */
    char detail[200];  /* what is wrong with the XML */
} ssx_md_error;

/* The attributes of the root, CoSimulation, ModelExchange and DefaultExperiment elements
 * (the last of each kind). Every text in an ssx_md is an offset into its string pool of
 * NUL-terminated UTF-8 (entities resolved), 0 meaning absent. */
typedef struct {
    uint32_t element;
    uint32_t name;
    uint32_t value;
} ssx_md_attribute;

typedef struct {
    uint32_t name;
    uint32_t type;         /* the tag of its type element: "Real", ... */
    uint32_t description;
    uint32_t unit;
    uint32_t quantity;
} ssx_md_simple_type;

typedef struct ssx_md_names ssx_md_names;

typedef struct {
    ssx_md_error error;
    const char *strings;
    const ssx_md_attribute *attributes;
    size_t attribute_count;
    const ssx_md_simple_type *types;
    size_t type_count;
    /* The variables, in document order, one array per field. */
    size_t variable_count;
    const uint32_t *name;
    const uint32_t *value_reference;
    const uint32_t *description;
    const uint32_t *unit;          /* of Real variables only */
    const uint32_t *start;         /* the text of the XML */
    const int32_t *declared_type;  /* index into types, -1: none */
    const uint8_t *type;           /* ssx_md_word */
    const uint8_t *causality;      /* the FMI 2.0 default when absent: SSX_MD_LOCAL */
    const uint8_t *variability;    /* SSX_MD_CONTINUOUS when absent */
    const uint8_t *initial;        /* FMI 2.0's default when absent (may be SSX_MD_NONE) */
    const uint32_t *derivative;    /* a Real's derivative attribute (variable index from 1), 0: none */
    /* ModelStructure/Outputs: the output's variable index (from 0) and its dependencies
     * (variable indices, from 0) at dependencies[first_dependency[k]] onwards; a
     * dependency_count of -1 means the attribute is absent (depends on everything). */
    size_t output_count;
    const uint32_t *output;
    const size_t *first_dependency;
    const int64_t *dependency_count;
    const uint32_t *dependencies;
    size_t dependency_total;
    ssx_md_names *names;
    /* the Unknowns of ModelStructure/Derivatives: a Model Exchange FMU's continuous states */
    size_t derivative_count;
    /* variables named as an earlier one was (ssx_md_find gives the first of a name) */
    size_t duplicate_count;
} ssx_md;

/* Reads the modelDescription in xml[0..size). Returns NULL only when out of memory; otherwise
 * check error.problem (the arrays hold what was read before a problem). */
ssx_md *ssx_md_read(const char *xml, size_t size);
void ssx_md_free(ssx_md *md);
/* The index of the (first) variable called name (NUL-terminated UTF-8), or -1. */
int64_t ssx_md_find(const ssx_md *md, const char *name);
const char *ssx_md_word_text(int word); /* "calculatedParameter", "Real", ...; "" for none */
/* The texts at offsets[0..n) of md's pool (0: absent, written as ""), separated by NULs, into
 * out (out_size bytes, filled as far as it reaches). Returns the bytes all of them take: ask
 * with out_size 0, then read n texts in a single pass (what one call per text would cost
 * Python for every field of 10**5 variables). */
size_t ssx_md_join(const ssx_md *md, const uint32_t *offsets, size_t n, char *out,
                   size_t out_size);

#endif
