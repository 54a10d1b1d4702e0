/* The FMI 3.0 value table (see fmu_fmi3_context.h): each value reference's type, given at load; the
 * FMU's arrays, read and written whole; and every conversion between an engine port type and
 * an FMI 3.0 type, refusing a value that does not fit. */
#include "fmu_fmi3_context.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const type_names[SSX_FMI3_TYPE_COUNT] = {
    "Float64", "Float32", "Int8",  "UInt8",  "Int16",  "UInt16",
    "Int32",   "UInt32",  "Int64", "UInt64", "Boolean"};

/* The slot of each type's getter and setter. */
static const ssx_fmu_slot getter[SSX_FMI3_TYPE_COUNT] = {
    SLOT_GET_REAL,  SLOT_GET_FLOAT32, SLOT_GET_INT8,    SLOT_GET_UINT8,
    SLOT_GET_INT16, SLOT_GET_UINT16,  SLOT_GET_INTEGER, SLOT_GET_UINT32,
    SLOT_GET_INT64, SLOT_GET_UINT64,  SLOT_GET_BOOLEAN};
static const ssx_fmu_slot setter[SSX_FMI3_TYPE_COUNT] = {
    SLOT_SET_REAL,  SLOT_SET_FLOAT32, SLOT_SET_INT8,    SLOT_SET_UINT8,
    SLOT_SET_INT16, SLOT_SET_UINT16,  SLOT_SET_INTEGER, SLOT_SET_UINT32,
    SLOT_SET_INT64, SLOT_SET_UINT64,  SLOT_SET_BOOLEAN};

/* The engine port type each FMI 3.0 type is exchanged as. */
static ssx_value_type port_type(ssx_fmi3_type type)
{
    return type <= SSX_FMI3_FLOAT32   ? SSX_REAL
           : type == SSX_FMI3_BOOLEAN ? SSX_BOOLEAN
                                      : SSX_INTEGER;
}

/* ------------------------------------------------------------------ load */

static int by_value_reference(const void *a, const void *b)
{
    unsigned int x = ((const variable *)a)->vr, y = ((const variable *)b)->vr;
    return (x > y) - (x < y);
}

static int put_real(ssx_fmi3_type type, void *values, size_t k, double d);

/* The arrays the elements among `variables` belong to (ctx->variables in the given order),
 * each with its buffers and start values; every element points at its array. */
static int collect_arrays(fmi3_context *ctx, const ssx_fmi3_variables *variables, char *error,
                          size_t error_size)
{
    if (variables->fmu_vr == NULL || variables->element == NULL) {
        snprintf(error, error_size, "array sizes given without value references and elements");
        return -1;
    }
    size_t elements = 0;
    for (size_t i = 0; i < variables->n; ++i) {
        elements += variables->size[i] > 0;
    }
    ctx->arrays = calloc(elements > 0 ? elements : 1, sizeof *ctx->arrays);
    if (ctx->arrays == NULL) {
        snprintf(error, error_size, "out of memory keeping the FMU's arrays");
        return -1;
    }
    for (size_t i = 0; i < variables->n; ++i) {
        size_t size = variables->size[i], element = variables->element[i];
        if (size == 0) {
            continue;
        }
        variable *v = &ctx->variables[i];
        size_t j = ctx->n_arrays;
        while (j > 0 && ctx->arrays[j - 1].vr != variables->fmu_vr[i]) {
            --j;
        }
        if (j == 0) {
            unsigned char *block =
                size <= SIZE_MAX / (3 * sizeof(uint64_t)) ? calloc(3 * size, sizeof(uint64_t))
                                                          : NULL;
            if (block == NULL) {
                snprintf(error, error_size, "out of memory keeping the %zu elements of '%s'",
                         size, v->name);
                return -1;
            }
            /* 8 bytes per element hold any type: start, values and read share one block */
            ctx->arrays[ctx->n_arrays++] = (array){
                .vr = variables->fmu_vr[i],
                .type = v->type,
                .size = size,
                .start = block,
                .values = block + size * sizeof(uint64_t),
                .read = block + 2 * size * sizeof(uint64_t),
            };
            j = ctx->n_arrays;
        }
        array *a = &ctx->arrays[j - 1];
        if (a->size != size || a->type != v->type || element >= size) {
            snprintf(error, error_size,
                     "variable '%s': element %zu of a %zu-element %s array does not fit the "
                     "%zu-element %s array of value reference %u",
                     v->name, element, size, type_names[v->type], a->size, type_names[a->type],
                     a->vr);
            return -1;
        }
        double start = variables->start != NULL ? variables->start[i] : 0.0;
        if (put_real((ssx_fmi3_type)v->type, a->start, element, start) != 0) {
            snprintf(error, error_size, "variable '%s' (%s): start value %.17g does not fit",
                     v->name, type_names[v->type], start);
            return -1;
        }
        v->array = j;
        v->element = element;
    }
    for (size_t j = 0; j < ctx->n_arrays; ++j) {
        memcpy(ctx->arrays[j].values, ctx->arrays[j].start,
               ctx->arrays[j].size * sizeof(uint64_t));
    }
    return 0;
}

/* The periodic input clocks, each with a positive finite period and a finite shift. */
static int keep_clocks(fmi3_context *ctx, const ssx_fmi3_variables *variables, char *error,
                       size_t error_size)
{
    size_t n = variables != NULL && variables->clock_vr != NULL ? variables->n_clocks : 0;
    if (n == 0) {
        return 0;
    }
    ctx->clock_vr = malloc(n * sizeof *ctx->clock_vr);
    ctx->clock_period = malloc(n * sizeof *ctx->clock_period);
    ctx->clock_shift = malloc(n * sizeof *ctx->clock_shift);
    ctx->clock_active = malloc(n * sizeof *ctx->clock_active);
    if (ctx->clock_vr == NULL || ctx->clock_period == NULL || ctx->clock_shift == NULL ||
        ctx->clock_active == NULL) {
        snprintf(error, error_size, "out of memory keeping %zu clocks", n);
        return -1;
    }
    for (size_t i = 0; i < n; ++i) {
        double period = variables->clock_period[i], shift = variables->clock_shift[i];
        if (!(period > 0.0 && isfinite(period) && isfinite(shift))) {
            snprintf(error, error_size,
                     "clock (value reference %u): period %.17g and shift %.17g, a periodic "
                     "clock needs a positive finite period and a finite shift",
                     variables->clock_vr[i], period, shift);
            return -1;
        }
        ctx->clock_vr[i] = variables->clock_vr[i];
        ctx->clock_period[i] = period;
        ctx->clock_shift[i] = shift;
    }
    ctx->n_clocks = n;
    return 0;
}

/* The triggered input clocks and the output clocks: their value references. */
static int keep_triggered_and_output_clocks(fmi3_context *ctx,
                                            const ssx_fmi3_variables *variables, char *error,
                                            size_t error_size)
{
    if (variables == NULL) {
        return 0;
    }
    size_t n_triggered = variables->triggered_clock_vr != NULL ? variables->n_triggered_clocks : 0;
    size_t n_output = variables->output_clock_vr != NULL ? variables->n_output_clocks : 0;
    if (n_triggered > 0) {
        ctx->triggered_clock_vr = malloc(n_triggered * sizeof *ctx->triggered_clock_vr);
        if (ctx->triggered_clock_vr == NULL) {
            snprintf(error, error_size, "out of memory keeping %zu clocks", n_triggered);
            return -1;
        }
        memcpy(ctx->triggered_clock_vr, variables->triggered_clock_vr,
               n_triggered * sizeof *ctx->triggered_clock_vr);
        ctx->n_triggered_clocks = n_triggered;
    }
    if (n_output > 0) {
        ctx->output_clock_vr = malloc(n_output * sizeof *ctx->output_clock_vr);
        ctx->output_clock_active = malloc(n_output * sizeof *ctx->output_clock_active);
        ctx->output_clock_ticked = calloc(n_output, sizeof *ctx->output_clock_ticked);
        if (ctx->output_clock_vr == NULL || ctx->output_clock_active == NULL ||
            ctx->output_clock_ticked == NULL) {
            snprintf(error, error_size, "out of memory keeping %zu clocks", n_output);
            return -1;
        }
        memcpy(ctx->output_clock_vr, variables->output_clock_vr,
               n_output * sizeof *ctx->output_clock_vr);
        ctx->n_output_clocks = n_output;
    }
    return 0;
}

/* The countdown clocks: their value references, no tick planned yet. */
static int keep_countdown_clocks(fmi3_context *ctx, const ssx_fmi3_variables *variables,
                                 char *error, size_t error_size)
{
    size_t n = variables != NULL && variables->countdown_clock_vr != NULL
               ? variables->n_countdown_clocks : 0;
    if (n == 0) {
        return 0;
    }
    ctx->countdown_clock_vr = malloc(n * sizeof *ctx->countdown_clock_vr);
    ctx->countdown_next = malloc(n * sizeof *ctx->countdown_next);
    ctx->countdown_interval = malloc(n * sizeof *ctx->countdown_interval);
    ctx->countdown_answer = malloc(n * sizeof *ctx->countdown_answer);
    ctx->countdown_qualifier = malloc(n * sizeof *ctx->countdown_qualifier);
    ctx->countdown_active = malloc(n * sizeof *ctx->countdown_active);
    ctx->countdown_repeats = calloc(n, sizeof *ctx->countdown_repeats);
    if (ctx->countdown_clock_vr == NULL || ctx->countdown_next == NULL ||
        ctx->countdown_repeats == NULL ||
        ctx->countdown_interval == NULL || ctx->countdown_answer == NULL ||
        ctx->countdown_qualifier == NULL || ctx->countdown_active == NULL) {
        snprintf(error, error_size, "out of memory keeping %zu clocks", n);
        return -1;
    }
    memcpy(ctx->countdown_clock_vr, variables->countdown_clock_vr,
           n * sizeof *ctx->countdown_clock_vr);
    if (variables->countdown_clock_repeats != NULL) {
        memcpy(ctx->countdown_repeats, variables->countdown_clock_repeats,
               n * sizeof *ctx->countdown_repeats);
    }
    for (size_t i = 0; i < n; ++i) {
        ctx->countdown_next[i] = INFINITY;
        ctx->countdown_interval[i] = 0.0;
    }
    ctx->n_countdown_clocks = n;
    return 0;
}

int ssx_fmi3_prepare(void *context, const ssx_fmi3_variables *variables, char *error,
                     size_t error_size)
{
    fmi3_context *ctx = context;
    size_t n = variables != NULL ? variables->n : 0;
    size_t pool = 0;
    for (size_t i = 0; i < n; ++i) {
        if (variables->type[i] >= SSX_FMI3_TYPE_COUNT) {
            snprintf(error, error_size,
                     "value reference %u: FMI 3.0 type code %d is not an "
                     "ssx_fmi3_type",
                     variables->vr[i], variables->type[i]);
            return -1;
        }
        pool += strlen(variables->name[i] != NULL ? variables->name[i] : "") + 1;
    }
    ctx->variables = calloc(n > 0 ? n : 1, sizeof *ctx->variables);
    ctx->names = malloc(pool > 0 ? pool : 1);
    if (ctx->variables == NULL || ctx->names == NULL) {
        snprintf(error, error_size, "out of memory keeping the FMU's %zu variables", n);
        return -1;
    }
    char *at = ctx->names;
    for (size_t i = 0; i < n; ++i) {
        const char *name = variables->name[i] != NULL ? variables->name[i] : "";
        size_t length = strlen(name) + 1;
        memcpy(at, name, length);
        ctx->variables[i] = (variable){variables->vr[i], variables->type[i], at, 0, 0};
        at += length;
    }
    if (variables != NULL && variables->size != NULL &&
        collect_arrays(ctx, variables, error, error_size) != 0) {
        return -1;
    }
    qsort(ctx->variables, n, sizeof *ctx->variables, by_value_reference);
    ctx->n_variables = n;
    if (variables != NULL) {
        ctx->event_mode_used = variables->event_mode_used != 0;
        ctx->early_return_allowed = variables->early_return_allowed != 0;
    }
    size_t n_moving = variables != NULL && variables->intermediate_vr != NULL
                          ? variables->n_intermediate
                          : 0;
    if (n_moving > 0) {
        ctx->intermediate_vr = malloc(n_moving * sizeof *ctx->intermediate_vr);
        ctx->intermediate_base = calloc(4 * n_moving, sizeof *ctx->intermediate_base);
        if (ctx->intermediate_vr == NULL || ctx->intermediate_base == NULL) {
            snprintf(error, error_size, "out of memory keeping %zu intermediate inputs", n_moving);
            return -1;
        }
        memcpy(ctx->intermediate_vr, variables->intermediate_vr,
               n_moving * sizeof *ctx->intermediate_vr);
        ctx->n_intermediate = n_moving;
    }
    if (keep_clocks(ctx, variables, error, error_size) != 0) {
        return -1;
    }
    if (keep_triggered_and_output_clocks(ctx, variables, error, error_size) != 0) {
        return -1;
    }
    return keep_countdown_clocks(ctx, variables, error, error_size);
}

void fmi3_say(fmi3_context *ctx, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(ctx->environment->last_message, sizeof ctx->environment->last_message, format,
              args);
    va_end(args);
}

void fmi3_values_free(fmi3_context *ctx)
{
    for (size_t i = 0; i < ctx->n_arrays; ++i) {
        free(ctx->arrays[i].start);
    }
    free(ctx->arrays);
    free(ctx->variables);
    free(ctx->names);
    free(ctx->part_vr);
    free(ctx->part_at);
    free(ctx->part_values);
    free(ctx->intermediate_vr);
    free(ctx->intermediate_base);
    free(ctx->clock_vr);
    free(ctx->clock_period);
    free(ctx->clock_shift);
    free(ctx->clock_active);
    free(ctx->triggered_clock_vr);
    free(ctx->output_clock_vr);
    free(ctx->output_clock_active);
    free(ctx->output_clock_ticked);
    free(ctx->countdown_clock_vr);
    free(ctx->countdown_repeats);
    free(ctx->countdown_next);
    free(ctx->countdown_interval);
    free(ctx->countdown_answer);
    free(ctx->countdown_qualifier);
    free(ctx->countdown_active);
    free(ctx->countdown_states);
    free(ctx->countdown_plans);
}

void fmi3_values_reset(fmi3_context *ctx)
{
    for (size_t i = 0; i < ctx->n_arrays; ++i) {
        memcpy(ctx->arrays[i].values, ctx->arrays[i].start,
               ctx->arrays[i].size * sizeof(uint64_t));
    }
}

/* ------------------------------------------------------------------ values */

static const variable *find(const fmi3_context *ctx, unsigned int vr)
{
    size_t lo = 0, hi = ctx->n_variables;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (ctx->variables[mid].vr < vr) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo < ctx->n_variables && ctx->variables[lo].vr == vr ? &ctx->variables[lo] : NULL;
}

static int reserve_parts(fmi3_context *ctx, size_t n)
{
    if (n <= ctx->part_capacity) {
        return 0;
    }
    unsigned int *vr = realloc(ctx->part_vr, n * sizeof *vr);
    if (vr != NULL) {
        ctx->part_vr = vr;
    }
    size_t *at = realloc(ctx->part_at, n * sizeof *at);
    if (at != NULL) {
        ctx->part_at = at;
    }
    uint64_t *values = realloc(ctx->part_values, n * sizeof *values);
    if (values != NULL) {
        ctx->part_values = values;
    }
    if (vr == NULL || at == NULL || values == NULL) {
        fmi3_say(ctx, "out of memory batching %zu values", n);
        return -1;
    }
    ctx->part_capacity = n;
    return 0;
}

/* A variable of `type` travels as its own port family, an integer one also as Real. */
static int exchanged_as(ssx_fmi3_type type, ssx_value_type port)
{
    return port_type(type) == port || (port == SSX_REAL && port_type(type) == SSX_INTEGER);
}

/* Every vr is known and may travel as `port`. Returns their type when all are the same
 * scalar type, SSX_FMI3_TYPE_COUNT when they differ or one is an array element, -1 for an
 * unknown or foreign one. */
static int common_type(fmi3_context *ctx, ssx_value_type port, const unsigned int *vr, size_t n)
{
    int common = -1;
    for (size_t i = 0; i < n; ++i) {
        const variable *v = find(ctx, vr[i]);
        if (v == NULL) {
            fmi3_say(ctx, "value reference %u is not among the variables the FMU was loaded with",
                vr[i]);
            return -1;
        }
        if (!exchanged_as(v->type, port)) {
            fmi3_say(ctx, "variable '%s' (%s) is not exchanged as this port type", v->name,
                type_names[v->type]);
            return -1;
        }
        common = v->array != 0                        ? SSX_FMI3_TYPE_COUNT
                 : common < 0 || common == v->type ? v->type
                                                      : SSX_FMI3_TYPE_COUNT;
    }
    return common;
}

/* Whether values of `type` pass to `port` unconverted. */
static int direct(int type, ssx_value_type port)
{
    return (type == SSX_FMI3_FLOAT64 && port == SSX_REAL) ||
           (type == SSX_FMI3_INT32 && port == SSX_INTEGER);
}

/* Gathers the scalars of type `type` into the parts; returns how many. */
static size_t gather(fmi3_context *ctx, ssx_fmi3_type type, const unsigned int *vr, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        const variable *v = find(ctx, vr[i]);
        if (v->array == 0 && v->type == type) {
            ctx->part_vr[k] = vr[i];
            ctx->part_at[k++] = i;
        }
    }
    return k;
}

/* One fmi3GetX call of `type` for n value references into `values` (n_values of that type:
 * more than n when one is an array). */
static int get_typed(const ssx_fmu_function *fn, fmi3Instance instance, ssx_fmi3_type type,
                     const unsigned int *vr, size_t n, void *values, size_t n_values)
{
    ssx_fmu_function f = fn[getter[type]];
    if (f == NULL) {
        return fmi3Error; /* a Scheduled Execution binary need not export every type's call */
    }
    switch (type) {
    case SSX_FMI3_FLOAT64:
        return (int)((fmi3GetFloat64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_FLOAT32:
        return (int)((fmi3GetFloat32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT8:
        return (int)((fmi3GetInt8TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT8:
        return (int)((fmi3GetUInt8TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT16:
        return (int)((fmi3GetInt16TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT16:
        return (int)((fmi3GetUInt16TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT32:
        return (int)((fmi3GetInt32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT32:
        return (int)((fmi3GetUInt32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT64:
        return (int)((fmi3GetInt64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT64:
        return (int)((fmi3GetUInt64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_BOOLEAN:
        return (int)((fmi3GetBooleanTYPE *)f)(instance, vr, n, values, n_values);
    default:
        return fmi3Error;
    }
}

static int set_typed(const ssx_fmu_function *fn, fmi3Instance instance, ssx_fmi3_type type,
                     const unsigned int *vr, size_t n, const void *values, size_t n_values)
{
    ssx_fmu_function f = fn[setter[type]];
    if (f == NULL) {
        return fmi3Error; /* a Scheduled Execution binary need not export every type's call */
    }
    switch (type) {
    case SSX_FMI3_FLOAT64:
        return (int)((fmi3SetFloat64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_FLOAT32:
        return (int)((fmi3SetFloat32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT8:
        return (int)((fmi3SetInt8TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT8:
        return (int)((fmi3SetUInt8TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT16:
        return (int)((fmi3SetInt16TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT16:
        return (int)((fmi3SetUInt16TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT32:
        return (int)((fmi3SetInt32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT32:
        return (int)((fmi3SetUInt32TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_INT64:
        return (int)((fmi3SetInt64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_UINT64:
        return (int)((fmi3SetUInt64TYPE *)f)(instance, vr, n, values, n_values);
    case SSX_FMI3_BOOLEAN:
        return (int)((fmi3SetBooleanTYPE *)f)(instance, vr, n, values, n_values);
    default:
        return fmi3Error;
    }
}

/* Element k of an array of integer `type`, widened; unsigned ones above INT64_MAX clamp there
 * (they do not fit an int either way). */
static long long integer_at(ssx_fmi3_type type, const void *values, size_t k)
{
    switch (type) {
    case SSX_FMI3_INT8:
        return ((const int8_t *)values)[k];
    case SSX_FMI3_UINT8:
        return ((const uint8_t *)values)[k];
    case SSX_FMI3_INT16:
        return ((const int16_t *)values)[k];
    case SSX_FMI3_UINT16:
        return ((const uint16_t *)values)[k];
    case SSX_FMI3_INT32:
        return ((const int32_t *)values)[k];
    case SSX_FMI3_UINT32:
        return ((const uint32_t *)values)[k];
    case SSX_FMI3_INT64:
        return ((const int64_t *)values)[k];
    case SSX_FMI3_UINT64: {
        uint64_t u = ((const uint64_t *)values)[k];
        return u > (uint64_t)LLONG_MAX ? LLONG_MAX : (long long)u;
    }
    default:
        return 0;
    }
}

/* The range of integer `type`, within long long. */
static void integer_range(ssx_fmi3_type type, long long *lo, long long *hi)
{
    static const long long bounds[][2] = {
        [SSX_FMI3_INT8] = {INT8_MIN, INT8_MAX},    [SSX_FMI3_UINT8] = {0, UINT8_MAX},
        [SSX_FMI3_INT16] = {INT16_MIN, INT16_MAX}, [SSX_FMI3_UINT16] = {0, UINT16_MAX},
        [SSX_FMI3_INT32] = {INT32_MIN, INT32_MAX}, [SSX_FMI3_UINT32] = {0, UINT32_MAX},
        [SSX_FMI3_INT64] = {INT64_MIN, INT64_MAX}, [SSX_FMI3_UINT64] = {0, LLONG_MAX},
    };
    *lo = bounds[type][0];
    *hi = bounds[type][1];
}

static void put_integer(ssx_fmi3_type type, void *values, size_t k, long long value)
{
    switch (type) {
    case SSX_FMI3_INT8:
        ((int8_t *)values)[k] = (int8_t)value;
        break;
    case SSX_FMI3_UINT8:
        ((uint8_t *)values)[k] = (uint8_t)value;
        break;
    case SSX_FMI3_INT16:
        ((int16_t *)values)[k] = (int16_t)value;
        break;
    case SSX_FMI3_UINT16:
        ((uint16_t *)values)[k] = (uint16_t)value;
        break;
    case SSX_FMI3_INT32:
        ((int32_t *)values)[k] = (int32_t)value;
        break;
    case SSX_FMI3_UINT32:
        ((uint32_t *)values)[k] = (uint32_t)value;
        break;
    case SSX_FMI3_INT64:
        ((int64_t *)values)[k] = (int64_t)value;
        break;
    case SSX_FMI3_UINT64:
        ((uint64_t *)values)[k] = (uint64_t)value;
        break;
    default:
        break;
    }
}

/* Beyond 2^53 in magnitude a double no longer holds every integer: an integer variable
 * exchanged as a Real port carries its value exactly up to there and fails beyond. */
static const double EXACT_INTEGER = 9007199254740992.0;

/* Whether d is a whole number that integer `type` holds and a double carries exactly. */
static int whole_in_range(ssx_fmi3_type type, double d)
{
    long long lo, hi;
    integer_range(type, &lo, &hi);
    double low = lo < -EXACT_INTEGER ? -EXACT_INTEGER : (double)lo;
    double high = hi > EXACT_INTEGER ? EXACT_INTEGER : (double)hi;
    return d >= low && d <= high && (double)(long long)d == d;
}

/* Element k of `values` (of `type`) as a double: the Real port's value of a float or an
 * integer, or of a Boolean (1, 0). */
static double real_at(ssx_fmi3_type type, const void *values, size_t k)
{
    switch (type) {
    case SSX_FMI3_FLOAT64:
        return ((const double *)values)[k];
    case SSX_FMI3_FLOAT32:
        return (double)((const float *)values)[k];
    case SSX_FMI3_BOOLEAN:
        return ((const bool *)values)[k] ? 1.0 : 0.0;
    case SSX_FMI3_UINT64:
        return (double)((const uint64_t *)values)[k];
    default:
        return (double)integer_at(type, values, k);
    }
}

/* Stores d as element k of `values` (of `type`); -1 when an integer type cannot hold it. */
static int put_real(ssx_fmi3_type type, void *values, size_t k, double d)
{
    switch (type) {
    case SSX_FMI3_FLOAT64:
        ((double *)values)[k] = d;
        return 0;
    case SSX_FMI3_FLOAT32:
        ((float *)values)[k] = (float)d;
        return 0;
    case SSX_FMI3_BOOLEAN:
        ((bool *)values)[k] = d != 0.0;
        return 0;
    default:
        if (!whole_in_range(type, d)) {
            return -1;
        }
        put_integer(type, values, k, (long long)d);
        return 0;
    }
}

/* Converts element k of `values` (v's type) into the engine's array `out` of port type `port`
 * at `at`; 0, or -1 when the value does not fit. */
static int take(fmi3_context *ctx, const variable *v, const void *values, size_t k,
                ssx_value_type port, void *out, size_t at)
{
    ssx_fmi3_type type = (ssx_fmi3_type)v->type;
    if (port == SSX_REAL) {
        double value = real_at(type, values, k);
        if (port_type(type) == SSX_INTEGER && !(value >= -EXACT_INTEGER && value <= EXACT_INTEGER)) {
            if (type == SSX_FMI3_UINT64) {
                fmi3_say(ctx,
                    "variable '%s' (UInt64) holds %llu, beyond 2^53, the largest magnitude "
                    "up to which the engine's Real ports carry integers exactly",
                    v->name, (unsigned long long)((const uint64_t *)values)[k]);
            } else {
                fmi3_say(ctx,
                    "variable '%s' (%s) holds %lld, beyond 2^53, the largest magnitude up to "
                    "which the engine's Real ports carry integers exactly",
                    v->name, type_names[type], integer_at(type, values, k));
            }
            return -1;
        }
        ((double *)out)[at] = value;
        return 0;
    }
    if (port == SSX_BOOLEAN) {
        ((int *)out)[at] = ((const bool *)values)[k] ? 1 : 0;
        return 0;
    }
    long long value = integer_at(type, values, k);
    if (value < INT_MIN || value > INT_MAX) {
        if (type == SSX_FMI3_UINT64) {
            fmi3_say(ctx,
                "variable '%s' (UInt64) holds %llu, outside the range of the engine's "
                "Integer ports (%d..%d)",
                v->name, (unsigned long long)((const uint64_t *)values)[k], INT_MIN, INT_MAX);
        } else {
            fmi3_say(ctx,
                "variable '%s' (%s) holds %lld, outside the range of the engine's Integer "
                "ports (%d..%d)",
                v->name, type_names[type], value, INT_MIN, INT_MAX);
        }
        return -1;
    }
    ((int *)out)[at] = (int)value;
    return 0;
}

/* Converts the engine's value at `at` of `in` into element k of `values` (v's type); -1 when
 * it does not fit the type. */
static int give(fmi3_context *ctx, const variable *v, void *values, size_t k,
                ssx_value_type port, const void *in, size_t at)
{
    ssx_fmi3_type type = (ssx_fmi3_type)v->type;
    if (port == SSX_REAL) {
        double value = ((const double *)in)[at];
        if (put_real(type, values, k, value) != 0) {
            long long lo, hi;
            integer_range(type, &lo, &hi);
            /* the range first: casting a double beyond long long is undefined */
            if (!(value > -EXACT_INTEGER && value < EXACT_INTEGER) ||
                value == (double)(long long)value) {
                fmi3_say(ctx,
                    "variable '%s' (%s) cannot take %.17g: outside %.17g..%.17g (its range, "
                    "within the 2^53 up to which the engine's Real ports carry integers "
                    "exactly)",
                    v->name, type_names[type], value,
                    lo < -EXACT_INTEGER ? -EXACT_INTEGER : (double)lo,
                    hi > EXACT_INTEGER ? EXACT_INTEGER : (double)hi);
            } else {
                fmi3_say(ctx, "variable '%s' (%s) cannot take %.17g: not a whole number", v->name,
                    type_names[type], value);
            }
            return -1;
        }
        return 0;
    }
    int value = ((const int *)in)[at];
    if (port == SSX_BOOLEAN) {
        ((bool *)values)[k] = value != 0;
        return 0;
    }
    long long lo, hi;
    integer_range(type, &lo, &hi);
    if (value < lo || value > hi) {
        fmi3_say(ctx, "variable '%s' (%s) cannot take %d: outside %lld..%lld", v->name,
            type_names[type], value, lo, hi);
        return -1;
    }
    put_integer(type, values, k, value);
    return 0;
}

/* Whether a status (or -1, a value that did not fit) lets the call go on. */
static int usable(int status)
{
    return status == fmi3OK || status == fmi3Warning;
}

static array *array_of(fmi3_context *ctx, const variable *v)
{
    return v->array != 0 ? &ctx->arrays[v->array - 1] : NULL;
}

/* The array elements among vr: each array read whole, once per call. */
static int get_elements(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                        const unsigned int *vr, size_t n, void *out)
{
    int result = fmi3OK;
    for (size_t i = 0; i < n && usable(result); ++i) {
        const variable *v = find(ctx, vr[i]);
        array *a = array_of(ctx, v);
        if (a == NULL) {
            continue;
        }
        if (!a->fresh) {
            result = worse_status(result, get_typed(fn, ctx->instance, (ssx_fmi3_type)a->type, &a->vr,
                                             1, a->read, a->size));
            a->fresh = 1;
        }
        if (usable(result) && take(ctx, v, a->read, v->element, port, out, i) != 0) {
            result = -1;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        array *a = array_of(ctx, find(ctx, vr[i]));
        if (a != NULL) {
            a->fresh = 0;
        }
    }
    return result;
}

/* The array elements among vr: each array written whole, once per call, its other elements
 * as last written (their start values until then). */
static int set_elements(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                        const unsigned int *vr, size_t n, const void *in)
{
    int result = fmi3OK;
    for (size_t i = 0; i < n && result == fmi3OK; ++i) {
        const variable *v = find(ctx, vr[i]);
        array *a = array_of(ctx, v);
        if (a != NULL) {
            result = give(ctx, v, a->values, v->element, port, in, i);
            a->pending = 1;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        array *a = array_of(ctx, find(ctx, vr[i]));
        if (a != NULL && a->pending) {
            a->pending = 0;
            if (usable(result)) {
                result = worse_status(result, set_typed(fn, ctx->instance, (ssx_fmi3_type)a->type,
                                                 &a->vr, 1, a->values, a->size));
            }
        }
    }
    return result;
}

int fmi3_get_values(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                    const unsigned int *vr, size_t n, void *out)
{
    int common = common_type(ctx, port, vr, n);
    if (common < 0) {
        return -1;
    }
    /* the usual case: nothing to convert */
    if (direct(common, port)) {
        return get_typed(fn, ctx->instance, (ssx_fmi3_type)common, vr, n, out, n);
    }
    if (reserve_parts(ctx, n) != 0) {
        return -1;
    }
    int worst = fmi3OK;
    for (int type = 0; type < SSX_FMI3_TYPE_COUNT; ++type) {
        if (!exchanged_as((ssx_fmi3_type)type, port)) {
            continue;
        }
        size_t m = gather(ctx, (ssx_fmi3_type)type, vr, n);
        if (m == 0) {
            continue;
        }
        int status = get_typed(fn, ctx->instance, (ssx_fmi3_type)type, ctx->part_vr, m,
                               ctx->part_values, m);
        worst = worse_status(worst, status);
        if (status > fmi3Warning) {
            return status;
        }
        for (size_t k = 0; k < m; ++k) {
            if (take(ctx, find(ctx, ctx->part_vr[k]), ctx->part_values, k, port, out,
                     ctx->part_at[k]) != 0) {
                return -1;
            }
        }
    }
    int status = get_elements(fn, ctx, port, vr, n, out);
    return status < 0 ? status : worse_status(worst, status);
}

int fmi3_set_values(const ssx_fmu_function *fn, fmi3_context *ctx, ssx_value_type port,
                    const unsigned int *vr, size_t n, const void *in)
{
    int common = common_type(ctx, port, vr, n);
    if (common < 0) {
        return -1;
    }
    if (direct(common, port)) {
        return set_typed(fn, ctx->instance, (ssx_fmi3_type)common, vr, n, in, n);
    }
    if (reserve_parts(ctx, n) != 0) {
        return -1;
    }
    int worst = fmi3OK;
    for (int type = 0; type < SSX_FMI3_TYPE_COUNT; ++type) {
        if (!exchanged_as((ssx_fmi3_type)type, port)) {
            continue;
        }
        size_t m = gather(ctx, (ssx_fmi3_type)type, vr, n);
        if (m == 0) {
            continue;
        }
        for (size_t k = 0; k < m; ++k) {
            if (give(ctx, find(ctx, ctx->part_vr[k]), ctx->part_values, k, port, in,
                     ctx->part_at[k]) != 0) {
                return -1;
            }
        }
        int status = set_typed(fn, ctx->instance, (ssx_fmi3_type)type, ctx->part_vr, m,
                               ctx->part_values, m);
        worst = worse_status(worst, status);
        if (status > fmi3Warning) {
            return status;
        }
    }
    int status = set_elements(fn, ctx, port, vr, n, in);
    return status < 0 ? status : worse_status(worst, status);
}

const char *fmi3_variable_name(const fmi3_context *ctx, unsigned int vr)
{
    const variable *v = find(ctx, vr);
    return v != NULL ? v->name : NULL;
}
