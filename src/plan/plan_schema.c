/* The plan format's keywords and what each takes: one table shared by the reader, the writer
 * and the builder.
 *
 * Signature letters (each one value unless said):
 *   c  a component defined before     o  an output of the last c     n  an input of the last c
 *   x  an indicator defined before    i  an int                       z  a count or size >= 0
 *   u  a value reference (32 bits)    f  a flag, 0 or 1               D  a direction -1, 0, 1
 *   V  an FMI version 1, 2 or 3       d  a double                     s  a string
 *   v  a double or a string (a start value)
 *   T, 3, K, G, J, L  a word: value type, FMI 3.0 type, event source, coupling, loop
 *      Jacobian, locator
 *   [ ... ]  a list: a count, then that many items of the signature inside
 *   g  a schedule group: its size, a flag (a loop), then that many components */
#include <string.h>

#include "event_source.h"
#include "locator.h"
#include "plan.h"

const plan_record_schema plan_schema[PLAN_RECORD_KIND_COUNT] = {
    [PLAN_SYSTEM] = {"system", "s", "NAME"},
    [PLAN_EXPERIMENT] = {"experiment", "ddd", "START STOP STEP"},
    [PLAN_FMU] = {"fmu", "sfVssssf",
                  "NAME CAN_GET_SET_STATE VERSION FOLDER MODEL_IDENTIFIER TOKEN INSTANCE_NAME "
                  "LOGGING_ON"},
    [PLAN_MODEL_EXCHANGE] = {"model_exchange", "sfzzVssssf",
                             "NAME CAN_GET_SET_STATE N_STATES N_EVENT_INDICATORS VERSION FOLDER "
                             "MODEL_IDENTIFIER TOKEN INSTANCE_NAME LOGGING_ON"},
    [PLAN_TABLE] = {"table", "s[d]", "NAME TIMES"},
    [PLAN_TABLE_COLUMN] = {"table_column", "cTf[d]", "COMPONENT TYPE HOLD VALUES"},
    [PLAN_PYTHON] = {"python", "sf", "NAME CAN_SNAPSHOT"},
    [PLAN_FMU_EXPERIMENT] = {"fmu_experiment", "cfdfd",
                             "COMPONENT TOLERANCE_DEFINED TOLERANCE STOP_DEFINED STOP"},
    [PLAN_START] = {"start", "cTuv", "COMPONENT TYPE VR VALUE"},
    [PLAN_ISOLATED] = {"isolated", "cd", "COMPONENT STEP_TIMEOUT"},
    [PLAN_FMI3_VARIABLES] = {"fmi3_variables", "cff",
                             "COMPONENT EVENT_MODE_USED EARLY_RETURN_ALLOWED"},
    [PLAN_FMI3_VARIABLE] = {"fmi3_variable", "cu3s", "COMPONENT VR FMI3TYPE NAME"},
    [PLAN_FMI3_ELEMENT] = {"fmi3_element", "cu3suzzd",
                           "COMPONENT VR FMI3TYPE NAME FMU_VR ELEMENT SIZE START"},
    [PLAN_FMI3_INTERMEDIATE] = {"fmi3_intermediate", "cu", "COMPONENT VR"},
    [PLAN_FMI3_CLOCK] = {"fmi3_clock", "cudd", "COMPONENT VR PERIOD SHIFT"},
    [PLAN_OUTPUT] = {"output", "cTu", "COMPONENT TYPE VR"},
    [PLAN_INPUT] = {"input", "cTuv", "COMPONENT TYPE VR START"},
    [PLAN_CONNECT] = {"connect", "cocndd",
                      "SRC_COMPONENT SRC_OUTPUT DST_COMPONENT DST_INPUT SCALE OFFSET"},
    [PLAN_INDICATOR_OUTPUT] = {"indicator_output", "coD", "COMPONENT OUTPUT DIRECTION"},
    [PLAN_INDICATOR_CALLBACK] = {"indicator_callback", "cD", "COMPONENT DIRECTION"},
    [PLAN_INDICATOR_SLOPE] = {"indicator_slope", "xu", "INDICATOR VR"},
    [PLAN_SUBSCRIBE] = {"subscribe", "Kzc", "KIND INDEX LISTENER"},
    [PLAN_RESTART_HANDLER] = {"restart_handler", "cfdfd[ud][ui][uf][uodd]",
                              "COMPONENT TOLERANCE_DEFINED TOLERANCE STOP_DEFINED STOP "
                              "REAL_STARTS INTEGER_STARTS BOOLEAN_STARTS TERMS"},
    [PLAN_SCHEDULE] = {"schedule", "[g]", "GROUPS"},
    [PLAN_COUPLING] = {"coupling", "G", "COUPLING"},
    [PLAN_THREADS] = {"threads", "i", "N"},
    [PLAN_CALLING_THREAD_ONLY] = {"calling_thread_only", "cf", "COMPONENT ON"},
    [PLAN_LOOP_OPTIONS] = {"loop_options", "did", "TOLERANCE MAX_ITERATIONS DAMPING"},
    [PLAN_LOOP_JACOBIAN] = {"loop_jacobian", "J", "JACOBIAN"},
    [PLAN_DIRECTIONAL_DERIVATIVES] = {"directional_derivatives", "cf", "COMPONENT PROVIDED"},
    [PLAN_INTERPOLATION] = {"interpolation", "cfi",
                            "COMPONENT CAN_INTERPOLATE_INPUTS MAX_OUTPUT_DERIVATIVE_ORDER"},
    [PLAN_INPUT_ORDER] = {"input_order", "i", "N"},
    [PLAN_EXTRAPOLATE_HELD_INPUTS] = {"extrapolate_held_inputs", "f", "ON"},
    [PLAN_STEP_CONTROL] = {"step_control", "ffddddddddfddf",
                           "ENABLED ROLLBACK RTOL ATOL MIN_STEP MAX_STEP INITIAL_STEP SAFETY "
                           "MIN_CHANGE MAX_CHANGE ENERGY PROPORTIONAL_GAIN INTEGRAL_GAIN STRICT"},
    [PLAN_POWER_BONDS] = {"power_bonds", "[cncn]", "BONDS"},
    [PLAN_HYBRID_OPTIONS] = {"hybrid_options", "ddiifLd",
                             "TOL_TIME TOL_VALUE MAX_ITERATIONS MAX_MICROSTEPS "
                             "RECORD_INTERNAL_STEPS LOCATOR ZENO_MIN_INTERVAL"},
    [PLAN_ALLOW_NON_FINITE] = {"allow_non_finite", "f", "ON"},
    [PLAN_OUTPUT_INTERVAL] = {"output_interval", "i", "GRID_STEPS"},
    [PLAN_RUN_OUTPUT_INTERVAL] = {"run_output_interval", "i", "GRID_STEPS"},
    [PLAN_HISTORY] = {"history", "f", "KEEP"},
    [PLAN_HOOKS] = {"hooks", "c", "COMPONENT"},
    [PLAN_OUTPUT_CLOCK_SOURCE] = {"output_clock_source", "ci", "COMPONENT CLOCK"},
    [PLAN_CONNECT_CLOCK] = {"connect_clock", "Kzci", "KIND INDEX LISTENER CLOCK"},
    [PLAN_FMI3_TRIGGERED_CLOCK] = {"fmi3_triggered_clock", "cu", "COMPONENT VR"},
    [PLAN_FMI3_OUTPUT_CLOCK] = {"fmi3_output_clock", "cu", "COMPONENT VR"},
    [PLAN_SCHEDULED_EXECUTION] = {"scheduled_execution", "sssssf",
                                  "NAME FOLDER MODEL_IDENTIFIER TOKEN INSTANCE_NAME LOGGING_ON"},
    [PLAN_SCHEDULED_CLOCK] = {"scheduled_clock", "ciuiddf[d]",
                              "COMPONENT KIND VR PRIORITY INTERVAL SHIFT INTERVAL_TUNABLE TIMES"},
    [PLAN_SCHEDULED_CLOCK_OUTPUT] = {"scheduled_clock_output", "cio", "COMPONENT CLOCK OUTPUT"},
    [PLAN_FMI3_COUNTDOWN_CLOCK] = {"fmi3_countdown_clock", "cu", "COMPONENT VR"},
    [PLAN_FMI3_CHANGING_CLOCK] = {"fmi3_changing_clock", "cu", "COMPONENT VR"},
};

static const char *const value_types[] = {"real", "integer", "boolean", "string", "binary", NULL};
static const char *const fmi3_types[] = {"float64", "float32", "int8", "uint8", "int16",
                                         "uint16", "int32", "uint32", "int64", "uint64",
                                         "boolean", NULL};
static const char *const couplings[] = {"gauss_seidel", "jacobi", NULL};
static const char *const jacobians[] = {"auto", "finite_differences", NULL};

const char *const *plan_words(plan_word_set set)
{
    static const char *const *const sets[PLAN_WORD_SET_COUNT] = {
        [PLAN_WORDS_VALUE_TYPE] = value_types,
        [PLAN_WORDS_FMI3_TYPE] = fmi3_types,
        [PLAN_WORDS_SOURCE] = event_source_names,
        [PLAN_WORDS_COUPLING] = couplings,
        [PLAN_WORDS_JACOBIAN] = jacobians,
        [PLAN_WORDS_LOCATOR] = locator_names,
    };
    return sets[set];
}

int plan_record_kind_of(const char *keyword, size_t size)
{
    for (int k = 0; k < PLAN_RECORD_KIND_COUNT; ++k) {
        const char *name = plan_schema[k].keyword;
        if (strlen(name) == size && memcmp(name, keyword, size) == 0) {
            return k;
        }
    }
    return -1;
}

plan_cursor plan_record_values(const ssx_plan *plan, size_t record)
{
    size_t first = plan->first_value[record];
    return (plan_cursor){plan, first, first + plan->n_values[record]};
}

const plan_value *plan_next_value(plan_cursor *cursor)
{
    /* the reader checked every record against its signature, so a builder that follows the
     * signature stays inside the record; a read past it gives a zero value */
    static const plan_value none = {.kind = PLAN_INTEGER};
    if (cursor->next >= cursor->end) {
        return &none;
    }
    return &cursor->plan->values[cursor->next++];
}

int64_t plan_next_integer(plan_cursor *cursor)
{
    return plan_next_value(cursor)->as.integer;
}

double plan_next_double(plan_cursor *cursor)
{
    return plan_next_value(cursor)->as.real;
}

const char *plan_next_text(plan_cursor *cursor, size_t *size)
{
    const plan_value *value = plan_next_value(cursor);
    if (size != NULL) {
        *size = value->as.text.size;
    }
    return cursor->plan->pool + value->as.text.offset;
}
