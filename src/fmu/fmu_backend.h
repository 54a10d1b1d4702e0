/* What an FMI version adds to the FMU binding. The binding (fmu_binding.c) is version-neutral:
 * it loads the binary, resolves the back-end's function table, keeps the instance, its states
 * and counters, and checks every call in one place. A back-end (fmu_fmi1.c, fmu_fmi2.c,
 * fmu_fmi3.c) names its standard's functions and calls them with their own types. */
#ifndef SSX_FMU_BACKEND_H
#define SSX_FMU_BACKEND_H

#include <stdarg.h>
#include <stddef.h>

#include "fmu_environment.h"
#include "fmu_outcome.h"
#include "syssimx_engine.h"

/* The operations of the interface: a back-end resolves one function of its standard into each
 * slot it has. */
typedef enum {
    /* what every step calls first: their functions share a cache line of the binding */
    SLOT_DO_STEP,
    SLOT_GET_REAL,
    SLOT_SET_REAL,
    SLOT_INSTANTIATE,
    SLOT_FREE_INSTANCE,
    SLOT_SETUP_EXPERIMENT,
    SLOT_ENTER_INITIALIZATION_MODE,
    SLOT_EXIT_INITIALIZATION_MODE,
    SLOT_TERMINATE,
    SLOT_RESET,
    SLOT_GET_INTEGER,
    SLOT_GET_BOOLEAN,
    SLOT_SET_INTEGER,
    SLOT_SET_BOOLEAN,
    SLOT_GET_STATE,
    SLOT_SET_STATE,
    SLOT_FREE_STATE,
    SLOT_SERIALIZED_STATE_SIZE,
    SLOT_SERIALIZE_STATE,
    SLOT_DESERIALIZE_STATE,
    SLOT_DIRECTIONAL_DERIVATIVE,
    SLOT_SET_INPUT_DERIVATIVES,  /* FMI 2.0 only: FMI 3.0 has intermediate update instead */
    SLOT_GET_OUTPUT_DERIVATIVES,
    SLOT_GET_TERMINATED,
    SLOT_GET_LAST_SUCCESSFUL_TIME,
    /* Model Exchange */
    SLOT_SET_TIME,
    SLOT_SET_CONTINUOUS_STATES,
    SLOT_GET_CONTINUOUS_STATES,
    SLOT_GET_DERIVATIVES,
    SLOT_GET_EVENT_INDICATORS,
    SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES,
    SLOT_ENTER_EVENT_MODE,
    SLOT_NEW_DISCRETE_STATES,
    SLOT_ENTER_CONTINUOUS_TIME_MODE,
    SLOT_COMPLETED_INTEGRATOR_STEP,
    SLOT_GET_NUMBER_OF_CONTINUOUS_STATES, /* FMI 3.0 asks the instance */
    SLOT_GET_NUMBER_OF_EVENT_INDICATORS,
    /* FMI 3.0: the value types beyond the engine's three port types (Float64, Int32 and
     * Boolean fill the slots above), strings and binaries, step mode (event mode is above) */
    SLOT_GET_FLOAT32,
    SLOT_GET_INT8,
    SLOT_GET_UINT8,
    SLOT_GET_INT16,
    SLOT_GET_UINT16,
    SLOT_GET_UINT32,
    SLOT_GET_INT64,
    SLOT_GET_UINT64,
    SLOT_SET_FLOAT32,
    SLOT_SET_INT8,
    SLOT_SET_UINT8,
    SLOT_SET_INT16,
    SLOT_SET_UINT16,
    SLOT_SET_UINT32,
    SLOT_SET_INT64,
    SLOT_SET_UINT64,
    SLOT_GET_STRING,
    SLOT_SET_STRING,
    SLOT_GET_BINARY,
    SLOT_SET_BINARY,
    SLOT_ENTER_STEP_MODE,
    SLOT_SET_CLOCK,
    SLOT_GET_CLOCK,
    SLOT_GET_INTERVAL,
    SLOT_ACTIVATE_MODEL_PARTITION,
    SLOT_COUNT
} ssx_fmu_slot;

/* The status names of every FMI version, in the order of their values (0 OK ... 5 Pending);
 * X(name) makes one entry. */
#define SSX_STATUS_NAMES(X) X(OK) X(Warning) X(Discard) X(Error) X(Fatal) X(Pending)
enum { SSX_STATUS_FATAL = 4 };

/* A resolved function, kept untyped; each adapter converts it back to its standard's type. */
typedef void (*ssx_fmu_function)(void);

/* One row of a back-end's table: the standard's name of the function that fills `slot`, and
 * whether a binary without it is not of that standard at all. The same table resolves the
 * functions, checks the required ones and names the calls in messages. */
typedef struct {
    const char *name;
    ssx_fmu_slot slot;
    int required;
} ssx_fmu_function_row;

/* An FMI version's back-end. Each adapter receives the resolved functions by slot and the
 * instance its instantiate returned, and returns the standard's status as an int (0 OK,
 * 1 Warning, 2 Discard, 3 Error, 4 Fatal, 5 Pending: the order of ssx_status_name). The binding
 * calls an adapter only when its slot is filled and an instance is live. */
typedef struct {
    const char *standard; /* "FMI 2.0 Co-Simulation", for messages */
    ssx_fmu_interface interface;
    const char *version;  /* "FMI 2.0", for messages */
    const char *const *status_names; /* the standard's name of each status ("fmi2OK", ...) */
    const ssx_fmu_function_row *functions;
    size_t n_functions;
    /* bytes the back-end keeps per FMU (what the instance may point at until it is freed),
     * zeroed by the binding and passed to instantiate */
    size_t context_size;
    /* NULL on failure; environment is what the FMU's callbacks reach: where its log messages
     * go (ssx_fmu_environment_log) and, isolated, its host */
    void *(*instantiate)(const ssx_fmu_function *fn, void *context,
                         ssx_fmu_environment *environment, const char *instance_name,
                         const char *guid, const char *resource_uri, int logging_on);
    void (*free_instance)(const ssx_fmu_function *fn, void *instance);
    int (*setup_experiment)(const ssx_fmu_function *fn, void *instance, int tolerance_defined,
                            double tolerance, double start_time, int stop_time_defined,
                            double stop_time);
    int (*enter_initialization_mode)(const ssx_fmu_function *fn, void *instance);
    int (*exit_initialization_mode)(const ssx_fmu_function *fn, void *instance);
    int (*terminate)(const ssx_fmu_function *fn, void *instance);
    int (*reset)(const ssx_fmu_function *fn, void *instance);
    int (*get_real)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    double *values);
    int (*get_integer)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, int *values);
    int (*get_boolean)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, int *values);
    int (*set_real)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr, size_t n,
                    const double *values);
    int (*set_integer)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, const int *values);
    int (*set_boolean)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                       size_t n, const int *values);
    int (*do_step)(const ssx_fmu_function *fn, void *instance, double t, double h,
                   int no_set_state_prior);
    int (*get_state)(const ssx_fmu_function *fn, void *instance, void **state);
    int (*set_state)(const ssx_fmu_function *fn, void *instance, void *state);
    int (*free_state)(const ssx_fmu_function *fn, void *instance, void **state);
    int (*serialized_state_size)(const ssx_fmu_function *fn, void *instance, void *state,
                                 size_t *size);
    int (*serialize_state)(const ssx_fmu_function *fn, void *instance, void *state, char *bytes,
                           size_t size);
    int (*deserialize_state)(const ssx_fmu_function *fn, void *instance, const char *bytes,
                             size_t size, void **state);
    int (*directional_derivative)(const ssx_fmu_function *fn, void *instance,
                                  const unsigned int *unknowns, size_t n_unknowns,
                                  const unsigned int *knowns, size_t n_knowns,
                                  const double *dv_known, double *dv_unknown);
    int (*set_input_derivatives)(const ssx_fmu_function *fn, void *instance,
                                 const unsigned int *vr, size_t n, const int *order,
                                 const double *values);
    int (*get_output_derivatives)(const ssx_fmu_function *fn, void *instance,
                                  const unsigned int *vr, size_t n, const int *order,
                                  double *values);
    int (*get_terminated)(const ssx_fmu_function *fn, void *instance, int *terminated);
    int (*get_last_successful_time)(const ssx_fmu_function *fn, void *instance, double *time);
    /* Model Exchange, and event mode for FMI 3.0 Co-Simulation too (NULL in a back-end
     * without it) */
    int (*set_time)(const ssx_fmu_function *fn, void *instance, double time);
    int (*set_continuous_states)(const ssx_fmu_function *fn, void *instance, const double *x,
                                 size_t nx);
    int (*get_continuous_states)(const ssx_fmu_function *fn, void *instance, double *x,
                                 size_t nx);
    int (*get_derivatives)(const ssx_fmu_function *fn, void *instance, double *dx, size_t nx);
    int (*get_event_indicators)(const ssx_fmu_function *fn, void *instance, double *z,
                                size_t nz);
    int (*get_nominals_of_continuous_states)(const ssx_fmu_function *fn, void *instance,
                                             double *nominals, size_t nx);
    int (*enter_event_mode)(const ssx_fmu_function *fn, void *instance);
    int (*new_discrete_states)(const ssx_fmu_function *fn, void *instance,
                               ssx_fmu_event_info *info);
    int (*enter_continuous_time_mode)(const ssx_fmu_function *fn, void *instance);
    int (*completed_integrator_step)(const ssx_fmu_function *fn, void *instance,
                                     int no_set_state_prior, int *enter_event_mode,
                                     int *terminate_simulation);
    int (*get_number_of_continuous_states)(const ssx_fmu_function *fn, void *instance,
                                           size_t *n);
    int (*get_number_of_event_indicators)(const ssx_fmu_function *fn, void *instance,
                                          size_t *n);
    /* FMI 3.0 (NULL in a back-end without them) */
    int (*get_string)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                      size_t n, const char **values);
    int (*set_string)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                      size_t n, const char *const *values);
    int (*get_binary)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                      size_t n, size_t *sizes, const unsigned char **values);
    int (*set_binary)(const ssx_fmu_function *fn, void *instance, const unsigned int *vr,
                      size_t n, const size_t *sizes, const unsigned char *const *values);
    int (*enter_step_mode)(const ssx_fmu_function *fn, void *instance);
    /* in event mode at t: fmi3SetClock on every periodic input clock that ticks at t */
    int (*tick_clocks)(const ssx_fmu_function *fn, void *instance, double t);
    /* the first tick of a periodic input clock after t (not at t), INFINITY without one */
    double (*next_clock_tick)(const void *instance, double t);
    /* FMI 3.0 Co-Simulation in event mode: fmi3GetClock on the output clocks, active[k] set
     * for each (nothing is called without output clocks) */
    int (*read_output_clocks)(const ssx_fmu_function *fn, void *instance, int *active);
    /* in event mode: fmi3SetClock ticking the triggered input clock `clock` */
    int (*tick_triggered_clock)(const ssx_fmu_function *fn, void *instance, size_t clock);
    /* in Initialization or Event Mode at t: fmi3GetIntervalDecimal on the countdown clocks, and
     * each newly announced interval plans that clock's next tick (nothing is called without
     * countdown clocks) */
    int (*plan_clocks)(const ssx_fmu_function *fn, void *instance, double t);
    /* how many countdown clocks the load spec gave */
    size_t (*countdown_clocks)(const void *context);
    /* how many output clocks and triggered input clocks the load spec gave */
    void (*clock_counts)(const void *context, size_t *n_output, size_t *n_triggered);
    /* Scheduled Execution: fmi3ActivateModelPartition of input clock `clock` at t; its
     * clockUpdate callbacks read the output clocks and the countdown intervals (those read
     * with take_clock_updates) */
    int (*activate_model_partition)(const ssx_fmu_function *fn, void *instance,
                                    unsigned int clock, double t);
    /* what the partitions announced since the last take: ticked[k] for each output clock,
     * next[k] the tick of each countdown clock (INFINITY: none); then forgotten */
    void (*take_clock_updates)(void *context, int *ticked, double *next);
    /* fmi3GetIntervalDecimal of one clock */
    int (*get_interval)(const ssx_fmu_function *fn, void *instance, unsigned int clock,
                        double *interval, int *qualifier);
    /* what the last doStep said besides its status; NULL: only the status (FMI 2.0) */
    void (*step_outcome)(void *instance, fmu_step_outcome *outcome);
    /* the name of the variable vr, NULL when unknown; NULL: the back-end keeps no names */
    const char *(*variable_name)(const void *context, unsigned int vr);
    /* keeps what the back-end needs from the load spec in its zeroed context (-1, the reason
     * in error, on failure); NULL: nothing */
    int (*prepare)(void *context, const ssx_fmu_load_spec *spec, char *error,
                   size_t error_size);
    /* frees what the back-end put into its context at load; NULL: nothing */
    void (*release_context)(void *context);
} ssx_fmu_backend;

extern const ssx_fmu_backend ssx_fmi2_backend;
/* The same functions, instantiated as fmi2ModelExchange: a binary without the Model Exchange
 * functions is refused, one without fmi2DoStep is not. */
extern const ssx_fmu_backend ssx_fmi2_model_exchange_backend;
extern const ssx_fmu_backend ssx_fmi3_backend;
/* FMI 3.0 Model Exchange: fmi3InstantiateModelExchange, the Model Exchange functions instead
 * of fmi3DoStep and step mode; the same context and value adapters as Co-Simulation. */
extern const ssx_fmu_backend ssx_fmi3_model_exchange_backend;
/* FMI 3.0 Scheduled Execution: fmi3InstantiateScheduledExecution, then partitions activated
 * one at a time on the calling thread (fmi3ActivateModelPartition) in Clock Activation Mode. */
extern const ssx_fmu_backend ssx_fmi3_scheduled_backend;
/* FMI 1.0 Co-Simulation (fmiInstantiateSlave ... fmiDoStep) and Model Exchange
 * (fmiInstantiateModel ... fmiEventUpdate): no FMU state, no directional derivatives. */
extern const ssx_fmu_backend ssx_fmi1_backend;
extern const ssx_fmu_backend ssx_fmi1_model_exchange_backend;

#endif
