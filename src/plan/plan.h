/* A plan: a system as plain data (docs/reference/plan-format.md). Records in the order they
 * were read, each a keyword and its values; every value in one array, texts in one pool. The
 * schema (plan_schema.c) says what values each keyword takes, for the reader, the writer and
 * the builder alike. No system in here: plan_build.c makes one from a plan. */
#ifndef SSX_PLAN_H
#define SSX_PLAN_H

#include <stddef.h>
#include <stdint.h>

#include "syssimx_engine.h"

typedef enum {
    PLAN_SYSTEM, PLAN_EXPERIMENT,
    PLAN_FMU, PLAN_MODEL_EXCHANGE, PLAN_TABLE, PLAN_TABLE_COLUMN, PLAN_PYTHON,
    PLAN_FMU_EXPERIMENT, PLAN_START, PLAN_ISOLATED, PLAN_FMI3_VARIABLES, PLAN_FMI3_VARIABLE,
    PLAN_FMI3_ELEMENT, PLAN_FMI3_INTERMEDIATE, PLAN_FMI3_CLOCK,
    PLAN_OUTPUT, PLAN_INPUT, PLAN_CONNECT, PLAN_INDICATOR_OUTPUT, PLAN_INDICATOR_CALLBACK,
    PLAN_INDICATOR_SLOPE, PLAN_SUBSCRIBE, PLAN_RESTART_HANDLER,
    PLAN_SCHEDULE, PLAN_COUPLING, PLAN_THREADS, PLAN_CALLING_THREAD_ONLY, PLAN_LOOP_OPTIONS,
    PLAN_LOOP_JACOBIAN, PLAN_DIRECTIONAL_DERIVATIVES, PLAN_INTERPOLATION, PLAN_INPUT_ORDER,
    PLAN_EXTRAPOLATE_HELD_INPUTS, PLAN_STEP_CONTROL, PLAN_POWER_BONDS, PLAN_HYBRID_OPTIONS,
    PLAN_ALLOW_NON_FINITE, PLAN_OUTPUT_INTERVAL, PLAN_RUN_OUTPUT_INTERVAL, PLAN_HISTORY,
    PLAN_HOOKS, PLAN_OUTPUT_CLOCK_SOURCE, PLAN_CONNECT_CLOCK, PLAN_FMI3_TRIGGERED_CLOCK,
    PLAN_FMI3_OUTPUT_CLOCK, PLAN_FMI3_COUNTDOWN_CLOCK, PLAN_FMI3_CHANGING_CLOCK,
    PLAN_SCHEDULED_EXECUTION, PLAN_SCHEDULED_CLOCK, PLAN_SCHEDULED_CLOCK_OUTPUT,
    PLAN_RECORD_KIND_COUNT
} plan_record_kind;

typedef enum { PLAN_INTEGER, PLAN_DOUBLE, PLAN_STRING, PLAN_WORD } plan_value_kind;

/* A list of doubles longer than this is written in its hex form (`xN:` then 16 hex digits a
 * value), exact and fast both ways; a shorter one in decimal, readable. Python's writer keeps
 * the same bound, so that both write the same text. */
#define PLAN_DECIMAL_DOUBLES_MAX 64

/* The fixed word sets of the format. */
typedef enum {
    PLAN_WORDS_VALUE_TYPE, PLAN_WORDS_FMI3_TYPE, PLAN_WORDS_SOURCE, PLAN_WORDS_COUPLING,
    PLAN_WORDS_JACOBIAN, PLAN_WORDS_LOCATOR, PLAN_WORD_SET_COUNT
} plan_word_set;

typedef struct {
    uint8_t kind;     /* plan_value_kind */
    uint8_t word_set; /* plan_word_set of a PLAN_WORD */
    union {
        int64_t integer; /* PLAN_INTEGER, and a PLAN_WORD's index in its set */
        double real;
        struct {
            size_t offset; /* into the pool, where the bytes are followed by a NUL */
            size_t size;
        } text;
    } as;
} plan_value;

struct ssx_plan {
    size_t n_records;
    uint8_t *kind;       /* plan_record_kind */
    size_t *line;        /* where the record was read, 0 when made otherwise */
    size_t *first_value; /* the record's values are values[first_value[r]] onwards */
    size_t *n_values;
    plan_value *values;
    size_t n_values_total;
    char *pool;
    size_t pool_size;
    /* what the records define, by index: the components (the record that made each), their
     * outputs and inputs, the indicators */
    int n_components;
    size_t *component_record;
    int *n_outputs;
    int *n_inputs;
    int n_indicators;
};

/* The schema of one keyword: the values it takes (plan_schema.c explains the letters) and
 * the names of its fields, for messages. */
typedef struct {
    const char *keyword;
    const char *signature;
    const char *field_names; /* one space-separated name per top-level signature element */
} plan_record_schema;

extern const plan_record_schema plan_schema[PLAN_RECORD_KIND_COUNT];
/* The words of a set, NULL-terminated, in the order of their engine enum. */
const char *const *plan_words(plan_word_set set);
/* The record kind of a keyword of `size` bytes, or -1. */
int plan_record_kind_of(const char *keyword, size_t size);

/* Values of one record read in order (by the builder). */
typedef struct {
    const ssx_plan *plan;
    size_t next;
    size_t end;
} plan_cursor;

plan_cursor plan_record_values(const ssx_plan *plan, size_t record);
int64_t plan_next_integer(plan_cursor *cursor);
double plan_next_double(plan_cursor *cursor);
/* the text and its size (the bytes are NUL-terminated) */
const char *plan_next_text(plan_cursor *cursor, size_t *size);
/* the next value as it is: a string start value or a number */
const plan_value *plan_next_value(plan_cursor *cursor);

#endif
