/* The FMI 3.0 back-ends' instance (fmu_fmi3.c) and its value table (fmu_fmi3_values.c): the
 * type of every value reference, the FMU's arrays, and the conversion between the engine's
 * three port types and FMI 3.0's eleven. */
#ifndef SSX_FMU_FMI3_CONTEXT_H
#define SSX_FMU_FMI3_CONTEXT_H

#include <stddef.h>
#include <stdint.h>

#include "fmu_backend.h"

#include "fmi3Functions.h"

typedef struct {
    unsigned int vr; /* the engine's: the FMU's for a scalar, the element's own in an array */
    unsigned char type;
    const char *name; /* into the context's name pool */
    size_t array;     /* 1 + the index of its array among the context's, 0 for a scalar */
    size_t element;   /* its position in the array (row-major) */
} variable;

/* An FMU array variable: read and written whole, one fmi3Get/Set call per engine call. */
typedef struct {
    unsigned int vr; /* the FMU's */
    unsigned char type;
    size_t size;
    void *start;  /* the start values given at load */
    void *values; /* the values last written, start until then: a write completes with them */
    void *read;   /* the values last read */
    int fresh;    /* read during this engine call */
    int pending;  /* written during this engine call, not yet sent */
} array;

typedef struct {
    fmi3Instance instance; /* the FMU's; NULL until instantiated */
    ssx_fmu_environment *environment; /* where log messages go */
    variable *variables;   /* sorted by value reference */
    size_t n_variables;
    char *names;
    array *arrays;
    size_t n_arrays;
    int event_mode_used;
    int early_return_allowed;
    /* the experiment, kept for fmi3EnterInitializationMode */
    int tolerance_defined;
    double tolerance;
    double start_time;
    int stop_time_defined;
    double stop_time;
    fmu_step_outcome outcome;
    /* intermediate update (ssx_fmi3_variables): the inputs, their values at the step's start
     * and first and second derivatives, and values scratch; moving while a step uses them */
    unsigned int *intermediate_vr;
    size_t n_intermediate;
    double *intermediate_base; /* 4 * n_intermediate: base, first, second, scratch */
    int moving;
    double step_start;
    /* the periodic input clocks (ssx_fmi3_variables): ticks at start_time + shift + k period */
    unsigned int *clock_vr;
    double *clock_period;
    double *clock_shift;
    fmi3Clock *clock_active; /* scratch: which clocks tick at an instant */
    size_t n_clocks;
    /* the triggered input clocks and the output clocks (ssx_fmi3_variables) */
    unsigned int *triggered_clock_vr;
    size_t n_triggered_clocks;
    unsigned int *output_clock_vr;
    fmi3Clock *output_clock_active; /* scratch for fmi3GetClock */
    fmi3Clock *output_clock_ticked; /* Scheduled Execution: ticked in the running partition */
    size_t n_output_clocks;
    /* the countdown clocks (ssx_fmi3_variables): the next tick each is planned for (INFINITY:
     * none), the interval last announced, and scratch for the calls */
    unsigned int *countdown_clock_vr;
    unsigned char *countdown_repeats; /* tunable or changing: ticks every interval */
    double *countdown_next;
    double *countdown_interval;
    fmi3Float64 *countdown_answer;
    fmi3IntervalQualifier *countdown_qualifier;
    fmi3Clock *countdown_active;
    size_t n_countdown_clocks;
    /* the planned ticks saved with each FMU state the engine holds (a state set again brings
     * its plan back): states[k], and n_countdown_clocks values each in plans */
    void **countdown_states;
    double *countdown_plans;
    size_t n_countdown_states;
    /* Scheduled Execution: the partition running and its activation time, the worst status
     * of the calls its clockUpdate callbacks made, and the preemption lock's depth (below 0
     * once the FMU unlocked what it had not locked) */
    int in_partition;
    double partition_time;
    int update_status;
    int preemption_depth;
    const ssx_fmu_function *fn; /* for the callback */
    /* one type's part of a batch: value references, positions in the engine's call, values */
    unsigned int *part_vr;
    size_t *part_at;
    uint64_t *part_values; /* 8 bytes per value hold any numeric type */
    size_t part_capacity;
} fmi3_context;

/* The function in `slot` with its fmi3 type (ISO C converts between function pointer types). */
#define FMI3(fn, slot, type) ((type *)(fn)[slot])

static inline int worse_status(int a, int b)
{
    return a > b ? a : b;
}

/* The engine's own message about the instance (a trusted format), as its last message. */
void fmi3_say(fmi3_context *ctx, const char *format, ...);

/* The engine's get or set of `port` type: one fmi3 call per FMI 3.0 type among the scalars of
 * vr, one per array among its elements. */
int fmi3_get_values(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                    const unsigned int *vr, size_t n, void *out);
int fmi3_set_values(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                    const unsigned int *vr, size_t n, const void *in);
/* The name of the variable vr (NULL when the table has none). */
const char *fmi3_variable_name(const fmi3_context *ctx, unsigned int vr);
/* After fmi3Reset: the arrays hold their start values again. */
void fmi3_values_reset(fmi3_context *ctx);
void fmi3_values_free(fmi3_context *ctx);
/* The load-time facts, into the zeroed context: the type of every value reference the engine
 * gets or sets (copied) and how the FMU is instantiated. Fails (-1, the reason in error) when
 * out of memory or when a type is not an ssx_fmi3_type. */
int ssx_fmi3_prepare(void *context, const ssx_fmi3_variables *variables, char *error,
                     size_t error_size);

#endif
