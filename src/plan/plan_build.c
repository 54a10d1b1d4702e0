/* Building a system from a plan: the FMUs the caller did not give are loaded from their
 * unpacked folders, then each record makes its engine call in order. ssx_plan_initialize
 * makes the loaded FMUs ready as Python's System.initialize does, then initializes the
 * system. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "component.h"
#include "error.h"
#include "fmi3_type_table.h"
#include "plan.h"
#include "system.h"

typedef struct {
    const ssx_plan *plan;
    ssx_system *sys;
    char *error;
    size_t error_size;
    size_t record; /* the record being built, for messages */
} builder;

static int build_failed(builder *b, const char *format, ...) __attribute__((format(printf, 2, 3)));

static int build_failed(builder *b, const char *format, ...)
{
    if (b->error == NULL || b->error_size == 0) {
        return -1;
    }
    const ssx_plan *p = b->plan;
    int n = snprintf(b->error, b->error_size, "line %zu: record '%s': ", p->line[b->record],
                     plan_schema[p->kind[b->record]].keyword);
    if (n < 0 || (size_t)n >= b->error_size) {
        return -1;
    }
    va_list args;
    va_start(args, format);
    vsnprintf(b->error + n, b->error_size - (size_t)n, format, args);
    va_end(args);
    return -1;
}

/* An engine call's result: -1 names the engine's reason. */
static int engine_call(builder *b, int result)
{
    return result < 0 ? build_failed(b, "%s", ssx_last_error(b->sys)->message) : 0;
}

/* The record's component (its first value) for the records that name one, else -1. */
static int64_t component_of(const ssx_plan *p, size_t r)
{
    switch (p->kind[r]) {
    case PLAN_TABLE_COLUMN: case PLAN_FMU_EXPERIMENT: case PLAN_START: case PLAN_ISOLATED:
    case PLAN_FMI3_VARIABLES: case PLAN_FMI3_VARIABLE: case PLAN_FMI3_ELEMENT:
    case PLAN_FMI3_INTERMEDIATE: case PLAN_FMI3_CLOCK: case PLAN_FMI3_TRIGGERED_CLOCK:
    case PLAN_FMI3_OUTPUT_CLOCK: case PLAN_FMI3_COUNTDOWN_CLOCK: case PLAN_FMI3_CHANGING_CLOCK:
    case PLAN_OUTPUT:
    case PLAN_INPUT:
    case PLAN_RESTART_HANDLER:
        return p->values[p->first_value[r]].as.integer;
    default:
        return -1;
    }
}

/* n doubles of the record's values from the cursor on. */
static double *next_doubles(builder *b, plan_cursor *cursor, size_t n)
{
    double *out = malloc((n ? n : 1) * sizeof *out);
    if (out == NULL) {
        build_failed(b, "out of memory");
        return NULL;
    }
    for (size_t k = 0; k < n; ++k) {
        out[k] = plan_next_double(cursor);
    }
    return out;
}

/* ------------------------------------------------------------------ loading FMUs */
static char *joined(const char *a, const char *b, const char *c)
{
    size_t n = strlen(a) + strlen(b) + strlen(c) + 1;
    char *out = malloc(n);
    if (out != NULL) {
        snprintf(out, n, "%s%s%s", a, b, c);
    }
    return out;
}

/* The file: URI of an absolute path: every byte but the unreserved ones and '/' encoded. */
static char *file_uri(const char *path)
{
    size_t n = strlen(path);
    char *out = malloc(7 + 3 * n + 1);
    if (out == NULL) {
        return NULL;
    }
    size_t k = (size_t)sprintf(out, "file://");
    for (const unsigned char *s = (const unsigned char *)path; *s != '\0'; ++s) {
        int plain = (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
                    (*s >= '0' && *s <= '9') || strchr("/-._~", *s) != NULL;
        k += plain ? (size_t)sprintf(out + k, "%c", *s) : (size_t)sprintf(out + k, "%%%02X", *s);
    }
    return out;
}

/* The type table of an FMI 3.0 FMU: its fmi3_* records, or where it has no fmi3_variable and
 * no fmi3_element record, its modelDescription.xml's scalars (its flags too, unless an
 * fmi3_variables record gives them). */
typedef struct {
    ssx_fmi3_variables table;
    fmi3_type_table described;
    unsigned int *vr, *fmu_vr, *intermediate, *clock_vr, *triggered, *output_clocks, *countdown;
    unsigned char *type, *repeats; /* repeats: of each countdown clock, 1 for a changing one */
    const char **name;
    size_t *element, *size;
    double *start, *period, *shift;
} fmi3_table;

static void fmi3_table_free(fmi3_table *t)
{
    free(t->vr);
    free(t->fmu_vr);
    free(t->intermediate);
    free(t->clock_vr);
    free(t->triggered);
    free(t->output_clocks);
    free(t->countdown);
    free(t->repeats);
    free(t->type);
    free(t->name);
    free(t->element);
    free(t->size);
    free(t->start);
    free(t->period);
    free(t->shift);
    fmi3_type_table_free(&t->described);
}

/* The scalars of FOLDER/modelDescription.xml into t->described. */
static int fmi3_table_describe(builder *b, int component, const char *folder, fmi3_table *t)
{
    char *path = joined(folder, "/modelDescription.xml", "");
    FILE *file = path != NULL ? fopen(path, "rb") : NULL;
    char *xml = NULL;
    long size = -1;
    if (file != NULL && fseek(file, 0, SEEK_END) == 0 && (size = ftell(file)) >= 0 &&
        fseek(file, 0, SEEK_SET) == 0 && (xml = malloc((size_t)size + 1)) != NULL &&
        fread(xml, 1, (size_t)size, file) != (size_t)size) {
        size = -1;
    }
    if (file != NULL) {
        fclose(file);
    }
    char reason[512] = "";
    int result = xml == NULL || size < 0
                 ? build_failed(b, "component %d: cannot read %s (an FMI 3.0 FMU without "
                                   "fmi3_variable records needs it)",
                                component, path != NULL ? path : folder)
                 : fmi3_type_table_read(xml, (size_t)size, &t->described, reason, sizeof reason)
                   != 0 ? build_failed(b, "component %d: %s", component, reason) : 0;
    free(xml);
    free(path);
    return result;
}

static int fmi3_table_make(builder *b, int component, const char *folder, int model_exchange,
                           fmi3_table *t)
{
    const ssx_plan *p = b->plan;
    size_t n = 0, n_intermediate = 0, n_clocks = 0, n_triggered = 0, n_output_clocks = 0;
    size_t n_countdown = 0;
    int arrays = 0, flags_given = 0;
    for (size_t r = 0; r < p->n_records; ++r) {
        if (component_of(p, r) != component) {
            continue;
        }
        n += p->kind[r] == PLAN_FMI3_VARIABLE || p->kind[r] == PLAN_FMI3_ELEMENT;
        arrays |= p->kind[r] == PLAN_FMI3_ELEMENT;
        n_intermediate += p->kind[r] == PLAN_FMI3_INTERMEDIATE;
        n_clocks += p->kind[r] == PLAN_FMI3_CLOCK;
        n_triggered += p->kind[r] == PLAN_FMI3_TRIGGERED_CLOCK;
        n_output_clocks += p->kind[r] == PLAN_FMI3_OUTPUT_CLOCK;
        n_countdown += p->kind[r] == PLAN_FMI3_COUNTDOWN_CLOCK ||
                       p->kind[r] == PLAN_FMI3_CHANGING_CLOCK;
        flags_given |= p->kind[r] == PLAN_FMI3_VARIABLES;
    }
    if (n == 0 && fmi3_table_describe(b, component, folder, t) != 0) {
        return -1;
    }
    size_t slots = n ? n : 1;
    t->vr = calloc(slots, sizeof *t->vr);
    t->type = calloc(slots, sizeof *t->type);
    t->name = calloc(slots, sizeof *t->name);
    t->fmu_vr = calloc(slots, sizeof *t->fmu_vr);
    t->element = calloc(slots, sizeof *t->element);
    t->size = calloc(slots, sizeof *t->size);
    t->start = calloc(slots, sizeof *t->start);
    t->intermediate = calloc(n_intermediate ? n_intermediate : 1, sizeof *t->intermediate);
    t->clock_vr = calloc(n_clocks ? n_clocks : 1, sizeof *t->clock_vr);
    t->period = calloc(n_clocks ? n_clocks : 1, sizeof *t->period);
    t->shift = calloc(n_clocks ? n_clocks : 1, sizeof *t->shift);
    t->triggered = calloc(n_triggered ? n_triggered : 1, sizeof *t->triggered);
    t->output_clocks = calloc(n_output_clocks ? n_output_clocks : 1, sizeof *t->output_clocks);
    t->countdown = calloc(n_countdown ? n_countdown : 1, sizeof *t->countdown);
    t->repeats = calloc(n_countdown ? n_countdown : 1, sizeof *t->repeats);
    if (!t->vr || !t->type || !t->name || !t->fmu_vr || !t->element || !t->size || !t->start ||
        !t->intermediate || !t->clock_vr || !t->period || !t->shift || !t->triggered ||
        !t->output_clocks || !t->countdown || !t->repeats) {
        return build_failed(b, "out of memory");
    }
    size_t v = 0, i = 0, c = 0, triggered = 0, output_clocks = 0, countdown = 0;
    for (size_t r = 0; r < p->n_records; ++r) {
        if (component_of(p, r) != component) {
            continue;
        }
        plan_cursor cursor = plan_record_values(p, r);
        plan_next_integer(&cursor); /* the component */
        switch (p->kind[r]) {
        case PLAN_FMI3_VARIABLES:
            t->table.event_mode_used = (int)plan_next_integer(&cursor);
            t->table.early_return_allowed = (int)plan_next_integer(&cursor);
            break;
        case PLAN_FMI3_VARIABLE:
        case PLAN_FMI3_ELEMENT:
            t->vr[v] = (unsigned int)plan_next_integer(&cursor);
            t->type[v] = (unsigned char)plan_next_integer(&cursor);
            t->name[v] = plan_next_text(&cursor, NULL);
            t->fmu_vr[v] = t->vr[v];
            if (p->kind[r] == PLAN_FMI3_ELEMENT) {
                t->fmu_vr[v] = (unsigned int)plan_next_integer(&cursor);
                t->element[v] = (size_t)plan_next_integer(&cursor);
                t->size[v] = (size_t)plan_next_integer(&cursor);
                t->start[v] = plan_next_double(&cursor);
            }
            ++v;
            break;
        case PLAN_FMI3_INTERMEDIATE:
            t->intermediate[i++] = (unsigned int)plan_next_integer(&cursor);
            break;
        case PLAN_FMI3_CLOCK:
            t->clock_vr[c] = (unsigned int)plan_next_integer(&cursor);
            t->period[c] = plan_next_double(&cursor);
            t->shift[c++] = plan_next_double(&cursor);
            break;
        case PLAN_FMI3_TRIGGERED_CLOCK:
            t->triggered[triggered++] = (unsigned int)plan_next_integer(&cursor);
            break;
        case PLAN_FMI3_OUTPUT_CLOCK:
            t->output_clocks[output_clocks++] = (unsigned int)plan_next_integer(&cursor);
            break;
        case PLAN_FMI3_COUNTDOWN_CLOCK:
        case PLAN_FMI3_CHANGING_CLOCK:
            t->repeats[countdown] = p->kind[r] == PLAN_FMI3_CHANGING_CLOCK;
            t->countdown[countdown++] = (unsigned int)plan_next_integer(&cursor);
            break;
        default:
            break;
        }
    }
    t->table.vr = t->vr;
    t->table.type = t->type;
    t->table.name = t->name;
    t->table.n = n;
    if (n == 0) {
        t->table.vr = t->described.vr;
        t->table.type = t->described.type;
        t->table.name = (const char *const *)t->described.name;
        t->table.n = t->described.n;
        if (!flags_given) {
            t->table.event_mode_used = !model_exchange && t->described.has_event_mode;
            t->table.early_return_allowed = !model_exchange && t->described.may_return_early;
        }
    }
    if (arrays) {
        t->table.fmu_vr = t->fmu_vr;
        t->table.element = t->element;
        t->table.size = t->size;
        t->table.start = t->start;
    }
    t->table.intermediate_vr = n_intermediate ? t->intermediate : NULL;
    t->table.n_intermediate = n_intermediate;
    t->table.clock_vr = n_clocks ? t->clock_vr : NULL;
    t->table.clock_period = t->period;
    t->table.clock_shift = t->shift;
    t->table.n_clocks = n_clocks;
    t->table.triggered_clock_vr = n_triggered ? t->triggered : NULL;
    t->table.n_triggered_clocks = n_triggered;
    t->table.output_clock_vr = n_output_clocks ? t->output_clocks : NULL;
    t->table.n_output_clocks = n_output_clocks;
    t->table.countdown_clock_vr = n_countdown ? t->countdown : NULL;
    t->table.n_countdown_clocks = n_countdown;
    t->table.countdown_clock_repeats = n_countdown ? t->repeats : NULL;
    return 0;
}

/* Loads the FMU of component `component` (record `record`) from its folder. */
static ssx_fmu *load_fmu(builder *b, int component, const char *base_folder)
{
    const ssx_plan *p = b->plan;
    size_t record = p->component_record[component];
    b->record = record;
    for (size_t r = 0; r < p->n_records; ++r) {
        if (p->kind[r] == PLAN_ISOLATED && component_of(p, r) == component) {
            b->record = r;
            build_failed(b, "component %d runs in a host process, which only a caller that "
                            "loads it can give",
                         component);
            return NULL;
        }
    }
    plan_cursor cursor = plan_record_values(p, record);
    plan_next_text(&cursor, NULL);     /* the name */
    int scheduled = p->kind[record] == PLAN_SCHEDULED_EXECUTION; /* FMI 3.0, no state */
    if (!scheduled) {
        plan_next_integer(&cursor);    /* can_get_set_state */
    }
    int model_exchange = p->kind[record] == PLAN_MODEL_EXCHANGE;
    if (model_exchange) {
        plan_next_integer(&cursor);    /* states */
        plan_next_integer(&cursor);    /* event indicators */
    }
    int version = scheduled ? SSX_FMI3 : (int)plan_next_integer(&cursor);
    const char *folder = plan_next_text(&cursor, NULL);
    const char *model_identifier = plan_next_text(&cursor, NULL);
    const char *token = plan_next_text(&cursor, NULL);
    const char *instance_name = plan_next_text(&cursor, NULL);
    int logging_on = (int)plan_next_integer(&cursor);

    int relative = folder[0] != '/' && base_folder != NULL && base_folder[0] != '\0';
    char *given_path = relative ? joined(base_folder, "/", folder) : joined(folder, "", "");
    char *path = given_path != NULL ? realpath(given_path, NULL) : NULL;
    if (path == NULL) {
        build_failed(b, "component %d: its folder '%s' is not there", component,
                     given_path != NULL ? given_path : folder);
        free(given_path);
        return NULL;
    }
    free(given_path);
    const char *platform = version == SSX_FMI3 ? "/binaries/x86_64-linux/" : "/binaries/linux64/";
    char *binary_folder = joined(path, platform, model_identifier);
    char *binary = binary_folder != NULL ? joined(binary_folder, ".so", "") : NULL;
    char *resources = version == SSX_FMI3 ? joined(path, "/resources/", "")
                      : version == SSX_FMI2 ? joined(path, "/resources", "")
                      : joined(path, "", "");
    char *location = resources == NULL ? NULL
                     : version == SSX_FMI3 ? joined(resources, "", "") : file_uri(resources);
    fmi3_table table = {0};
    ssx_fmu *fmu = NULL;
    if (binary == NULL || location == NULL) {
        build_failed(b, "out of memory");
    } else if (version != SSX_FMI3 ||
               fmi3_table_make(b, component, path, model_exchange, &table) == 0) {
        ssx_fmu_load_spec spec = {
            .version = (ssx_fmi_version)version,
            .interface = scheduled        ? SSX_SCHEDULED_EXECUTION
                         : model_exchange ? SSX_MODEL_EXCHANGE
                                          : SSX_CO_SIMULATION,
            .binary_path = binary, .model_identifier = model_identifier, .guid = token,
            .resource_location = location,
            .instance_name = instance_name[0] != '\0' ? instance_name : NULL,
            .logging_on = logging_on,
            .fmi3_variables = version == SSX_FMI3 ? &table.table : NULL};
        char reason[1024];
        fmu = ssx_fmu_load(&spec, reason, sizeof reason);
        if (fmu == NULL) {
            b->record = record;
            build_failed(b, "component %d: %s", component, reason);
        }
    }
    fmi3_table_free(&table);
    free(path);
    free(binary_folder);
    free(binary);
    free(resources);
    free(location);
    return fmu;
}

/* ------------------------------------------------------------------ the records */
static int callback_not_attached(void *user, double t, double *value)
{
    (void)user;
    (void)t;
    *value = NAN;
    return -1;
}

static int build_table(builder *b, plan_cursor *cursor)
{
    const char *name = plan_next_text(cursor, NULL);
    size_t n = (size_t)plan_next_integer(cursor);
    double *time = next_doubles(b, cursor, n);
    if (time == NULL) {
        return -1;
    }
    int result = engine_call(b, ssx_add_table_component(b->sys, name, time, n));
    free(time);
    return result;
}

/* A Scheduled Execution component's clock, and the times of a triggered one. */
static int build_scheduled_clock(builder *b, plan_cursor *cursor)
{
    int c = (int)plan_next_integer(cursor);
    ssx_scheduled_clock_kind kind = (ssx_scheduled_clock_kind)plan_next_integer(cursor);
    unsigned int vr = (unsigned int)plan_next_integer(cursor);
    long long priority = (long long)plan_next_integer(cursor);
    double interval = plan_next_double(cursor);
    double shift = plan_next_double(cursor);
    int tunable = (int)plan_next_integer(cursor);
    size_t n = (size_t)plan_next_integer(cursor);
    double *times = next_doubles(b, cursor, n);
    if (times == NULL) {
        return -1;
    }
    int clock = ssx_add_scheduled_clock(b->sys, c, kind, vr, priority, interval, shift, tunable);
    int result = clock < 0 || (n == 0 && kind != SSX_SCHEDULED_TRIGGERED)
                 ? engine_call(b, clock)
                 : engine_call(b, ssx_set_scheduled_clock_times(b->sys, c, clock, times, n));
    free(times);
    return result;
}

static int build_table_column(builder *b, plan_cursor *cursor)
{
    int c = (int)plan_next_integer(cursor);
    ssx_value_type type = (ssx_value_type)plan_next_integer(cursor);
    int hold = (int)plan_next_integer(cursor);
    double *values = next_doubles(b, cursor, (size_t)plan_next_integer(cursor));
    if (values == NULL) {
        return -1;
    }
    int result = engine_call(b, ssx_add_table_column(b->sys, c, type, hold, values));
    free(values);
    return result;
}

static int build_input(builder *b, plan_cursor *cursor)
{
    int c = (int)plan_next_integer(cursor);
    ssx_value_type type = (ssx_value_type)plan_next_integer(cursor);
    unsigned int vr = (unsigned int)plan_next_integer(cursor);
    const plan_value *start = plan_next_value(cursor);
    double value = start->as.real;
    if (start->kind == PLAN_STRING &&
        ssx_bytes_number(b->sys, b->plan->pool + start->as.text.offset, start->as.text.size,
                         &value) != 0) {
        return build_failed(b, "out of memory");
    }
    return engine_call(b, ssx_add_input(b->sys, c, type, vr, value));
}

static int build_restart_handler(builder *b, plan_cursor *cursor)
{
    int c = (int)plan_next_integer(cursor);
    ssx_fmu_experiment experiment = {0};
    experiment.tolerance_defined = (int)plan_next_integer(cursor);
    experiment.tolerance = plan_next_double(cursor);
    experiment.stop_time_defined = (int)plan_next_integer(cursor);
    experiment.stop_time = plan_next_double(cursor);
    /* the three lists of starts, then the terms: read into arrays of their own */
    size_t n[3];
    unsigned int *vr[3] = {NULL, NULL, NULL};
    double *real = NULL;
    int *integer[2] = {NULL, NULL};
    unsigned int *target = NULL;
    int *source = NULL;
    double *scale = NULL, *offset = NULL;
    int result = -1;
    for (int list = 0; list < 3; ++list) {
        n[list] = (size_t)plan_next_integer(cursor);
        vr[list] = malloc((n[list] ? n[list] : 1) * sizeof(unsigned int));
        if (list == 0) {
            real = malloc((n[0] ? n[0] : 1) * sizeof *real);
        } else {
            integer[list - 1] = malloc((n[list] ? n[list] : 1) * sizeof(int));
        }
        if (vr[list] == NULL || (list == 0 ? real == NULL : integer[list - 1] == NULL)) {
            build_failed(b, "out of memory");
            goto done;
        }
        for (size_t k = 0; k < n[list]; ++k) {
            vr[list][k] = (unsigned int)plan_next_integer(cursor);
            if (list == 0) {
                real[k] = plan_next_double(cursor);
            } else {
                integer[list - 1][k] = (int)plan_next_integer(cursor);
            }
        }
    }
    size_t terms = (size_t)plan_next_integer(cursor);
    size_t slots = terms ? terms : 1;
    target = malloc(slots * sizeof *target);
    source = malloc(slots * sizeof *source);
    scale = malloc(slots * sizeof *scale);
    offset = malloc(slots * sizeof *offset);
    if (target == NULL || source == NULL || scale == NULL || offset == NULL) {
        build_failed(b, "out of memory");
        goto done;
    }
    for (size_t k = 0; k < terms; ++k) {
        target[k] = (unsigned int)plan_next_integer(cursor);
        source[k] = (int)plan_next_integer(cursor);
        scale[k] = plan_next_double(cursor);
        offset[k] = plan_next_double(cursor);
    }
    const ssx_fmu_values starts = {
        .real_vr = vr[0], .real_values = real, .n_real = n[0],
        .integer_vr = vr[1], .integer_values = integer[0], .n_integer = n[1],
        .boolean_vr = vr[2], .boolean_values = integer[1], .n_boolean = n[2]};
    result = engine_call(b, ssx_set_restart_handler(b->sys, c, &experiment, &starts, target,
                                                    source, scale, offset, terms));
done:
    for (int list = 0; list < 3; ++list) {
        free(vr[list]);
    }
    free(real);
    free(integer[0]);
    free(integer[1]);
    free(target);
    free(source);
    free(scale);
    free(offset);
    return result;
}

static int build_schedule(builder *b, plan_cursor *cursor)
{
    size_t groups = (size_t)plan_next_integer(cursor);
    /* every member is one value of the record: no more members than values */
    size_t most = b->plan->n_values[b->record];
    int *order = malloc(most * sizeof *order);
    int *sizes = malloc((groups ? groups : 1) * sizeof *sizes);
    int *loops = malloc((groups ? groups : 1) * sizeof *loops);
    int result = -1;
    if (order == NULL || sizes == NULL || loops == NULL) {
        build_failed(b, "out of memory");
    } else if (groups > INT_MAX) {
        build_failed(b, "too many groups");
    } else {
        size_t members = 0;
        for (size_t g = 0; g < groups; ++g) {
            sizes[g] = (int)plan_next_integer(cursor);
            loops[g] = (int)plan_next_integer(cursor);
            for (int k = 0; k < sizes[g]; ++k) {
                order[members++] = (int)plan_next_integer(cursor);
            }
        }
        result = engine_call(b, ssx_set_schedule(b->sys, order, sizes, loops, (int)groups));
    }
    free(order);
    free(sizes);
    free(loops);
    return result;
}

static int build_power_bonds(builder *b, plan_cursor *cursor)
{
    size_t bonds = (size_t)plan_next_integer(cursor);
    if (bonds > INT_MAX / 4) {
        return build_failed(b, "too many bonds");
    }
    int *ends = malloc((bonds ? 4 * bonds : 1) * sizeof *ends);
    if (ends == NULL) {
        return build_failed(b, "out of memory");
    }
    for (size_t k = 0; k < 4 * bonds; ++k) {
        ends[k] = (int)plan_next_integer(cursor);
    }
    int result = engine_call(b, ssx_set_power_bonds(b->sys, (int)bonds, ends));
    free(ends);
    return result;
}

static int build_step_control(builder *b, plan_cursor *cursor)
{
    ssx_step_control control;
    control.enabled = (int)plan_next_integer(cursor);
    control.rollback = (int)plan_next_integer(cursor);
    control.rtol = plan_next_double(cursor);
    control.atol = plan_next_double(cursor);
    control.min_step = plan_next_double(cursor);
    control.max_step = plan_next_double(cursor);
    control.initial_step = plan_next_double(cursor);
    control.safety = plan_next_double(cursor);
    control.min_change = plan_next_double(cursor);
    control.max_change = plan_next_double(cursor);
    control.energy = (int)plan_next_integer(cursor);
    control.proportional_gain = plan_next_double(cursor);
    control.integral_gain = plan_next_double(cursor);
    control.strict = (int)plan_next_integer(cursor);
    return engine_call(b, ssx_set_step_control(b->sys, &control));
}

static int build_hybrid_options(builder *b, plan_cursor *cursor)
{
    double tol_time = plan_next_double(cursor);
    double tol_value = plan_next_double(cursor);
    int max_iterations = (int)plan_next_integer(cursor);
    int max_microsteps = (int)plan_next_integer(cursor);
    int record_internal = (int)plan_next_integer(cursor);
    ssx_locator locator = (ssx_locator)plan_next_integer(cursor);
    double zeno = plan_next_double(cursor);
    return engine_call(b, ssx_set_hybrid_options(b->sys, tol_time, tol_value, max_iterations,
                                                 max_microsteps, record_internal, locator,
                                                 zeno));
}

static int build_record(builder *b, ssx_fmu *const *fmus)
{
    ssx_system *sys = b->sys;
    plan_cursor cursor = plan_record_values(b->plan, b->record);
    plan_cursor *v = &cursor;
    switch (b->plan->kind[b->record]) {
    case PLAN_FMU: {
        const char *name = plan_next_text(v, NULL);
        int can_state = (int)plan_next_integer(v);
        return engine_call(b, ssx_add_fmu_component(sys, name, fmus[sys->n_components],
                                                    can_state));
    }
    case PLAN_MODEL_EXCHANGE: {
        const char *name = plan_next_text(v, NULL);
        int can_state = (int)plan_next_integer(v);
        int64_t states = plan_next_integer(v), indicators = plan_next_integer(v);
        if (states > INT_MAX || indicators > INT_MAX) {
            return build_failed(b, "too many states or event indicators");
        }
        return engine_call(b, ssx_add_model_exchange_component(
                                  sys, name, fmus[sys->n_components], can_state, (int)states,
                                  (int)indicators));
    }
    case PLAN_SCHEDULED_EXECUTION:
        return engine_call(b, ssx_add_scheduled_component(sys, plan_next_text(v, NULL),
                                                          fmus[sys->n_components]));
    case PLAN_SCHEDULED_CLOCK:
        return build_scheduled_clock(b, v);
    case PLAN_SCHEDULED_CLOCK_OUTPUT: {
        int c = (int)plan_next_integer(v);
        int clock = (int)plan_next_integer(v);
        return engine_call(b, ssx_add_scheduled_clock_output(sys, c, clock,
                                                             (int)plan_next_integer(v)));
    }
    case PLAN_TABLE:
        return build_table(b, v);
    case PLAN_TABLE_COLUMN:
        return build_table_column(b, v);
    case PLAN_PYTHON: {
        const char *name = plan_next_text(v, NULL);
        return engine_call(b, ssx_add_python_component(sys, name, (int)plan_next_integer(v)));
    }
    case PLAN_OUTPUT: {
        int c = (int)plan_next_integer(v);
        ssx_value_type type = (ssx_value_type)plan_next_integer(v);
        return engine_call(b, ssx_add_output(sys, c, type, (unsigned int)plan_next_integer(v)));
    }
    case PLAN_INPUT:
        return build_input(b, v);
    case PLAN_CONNECT: {
        int src = (int)plan_next_integer(v), output = (int)plan_next_integer(v);
        int dst = (int)plan_next_integer(v), input = (int)plan_next_integer(v);
        double scale = plan_next_double(v);
        return engine_call(b, ssx_connect(sys, src, output, dst, input, scale,
                                          plan_next_double(v)));
    }
    case PLAN_INDICATOR_OUTPUT: {
        int c = (int)plan_next_integer(v), output = (int)plan_next_integer(v);
        return engine_call(b, ssx_add_indicator_output(sys, c, output,
                                                       (int)plan_next_integer(v)));
    }
    case PLAN_INDICATOR_CALLBACK: {
        int c = (int)plan_next_integer(v);
        return engine_call(b, ssx_add_indicator_callback(sys, c, callback_not_attached, NULL,
                                                         (int)plan_next_integer(v)));
    }
    case PLAN_INDICATOR_SLOPE: {
        int indicator = (int)plan_next_integer(v);
        return engine_call(b, ssx_set_indicator_slope(sys, indicator,
                                                      (unsigned int)plan_next_integer(v)));
    }
    case PLAN_SUBSCRIBE: {
        ssx_event_source_kind kind = (ssx_event_source_kind)plan_next_integer(v);
        int64_t index = plan_next_integer(v);
        if (index > INT_MAX) {
            return build_failed(b, "no source %lld", (long long)index);
        }
        return engine_call(b, ssx_subscribe(sys, kind, (int)index, (int)plan_next_integer(v)));
    }
    case PLAN_OUTPUT_CLOCK_SOURCE: {
        int c = (int)plan_next_integer(v);
        int result = ssx_add_output_clock_source(sys, c, (int)plan_next_integer(v));
        return result < 0 ? engine_call(b, result) : 0;
    }
    case PLAN_CONNECT_CLOCK: {
        ssx_event_source_kind kind = (ssx_event_source_kind)plan_next_integer(v);
        int64_t index = plan_next_integer(v);
        if (index > INT_MAX) {
            return build_failed(b, "no source %lld", (long long)index);
        }
        int listener = (int)plan_next_integer(v);
        return engine_call(b, ssx_connect_clock(sys, kind, (int)index, listener,
                                                (int)plan_next_integer(v)));
    }
    case PLAN_RESTART_HANDLER:
        return build_restart_handler(b, v);
    case PLAN_SCHEDULE:
        return build_schedule(b, v);
    case PLAN_COUPLING:
        return engine_call(b, ssx_set_coupling(sys, (ssx_coupling)plan_next_integer(v)));
    case PLAN_THREADS:
        return engine_call(b, ssx_set_threads(sys, (int)plan_next_integer(v)));
    case PLAN_CALLING_THREAD_ONLY: {
        int c = (int)plan_next_integer(v);
        return engine_call(b, ssx_set_calling_thread_only(sys, c, (int)plan_next_integer(v)));
    }
    case PLAN_LOOP_OPTIONS: {
        double tolerance = plan_next_double(v);
        int max_iterations = (int)plan_next_integer(v);
        return engine_call(b, ssx_set_loop_options(sys, tolerance, max_iterations,
                                                   plan_next_double(v)));
    }
    case PLAN_LOOP_JACOBIAN:
        return engine_call(b, ssx_set_loop_jacobian(sys, (ssx_loop_jacobian)plan_next_integer(v)));
    case PLAN_DIRECTIONAL_DERIVATIVES: {
        int c = (int)plan_next_integer(v);
        return engine_call(b, ssx_set_directional_derivatives(sys, c, (int)plan_next_integer(v)));
    }
    case PLAN_INTERPOLATION: {
        int c = (int)plan_next_integer(v), can = (int)plan_next_integer(v);
        return engine_call(b, ssx_set_interpolation(sys, c, can, (int)plan_next_integer(v)));
    }
    case PLAN_INPUT_ORDER:
        return engine_call(b, ssx_set_input_order(sys, (int)plan_next_integer(v)));
    case PLAN_EXTRAPOLATE_HELD_INPUTS:
        return engine_call(b, ssx_set_extrapolate_held_inputs(sys, (int)plan_next_integer(v)));
    case PLAN_STEP_CONTROL:
        return build_step_control(b, v);
    case PLAN_POWER_BONDS:
        return build_power_bonds(b, v);
    case PLAN_HYBRID_OPTIONS:
        return build_hybrid_options(b, v);
    case PLAN_ALLOW_NON_FINITE:
        return engine_call(b, ssx_set_allow_non_finite(sys, (int)plan_next_integer(v)));
    case PLAN_OUTPUT_INTERVAL:
        return engine_call(b, ssx_set_output_interval(sys, (int)plan_next_integer(v)));
    case PLAN_RUN_OUTPUT_INTERVAL:
        return engine_call(b, ssx_set_run_output_interval(sys, (int)plan_next_integer(v)));
    case PLAN_HISTORY:
        return engine_call(b, ssx_set_history(sys, (int)plan_next_integer(v)));
    default: /* the system, the experiment, and what loading and initializing FMUs read */
        return 0;
    }
}

static int is_fmu_record(int kind)
{
    return kind == PLAN_FMU || kind == PLAN_MODEL_EXCHANGE || kind == PLAN_SCHEDULED_EXECUTION;
}

ssx_system *ssx_plan_build(const ssx_plan *plan, const char *base_folder, ssx_fmu *const *given,
                           size_t n_given, char *error, size_t error_size)
{
    if (error != NULL && error_size > 0) {
        error[0] = '\0';
    }
    if (plan == NULL || plan->n_records == 0) {
        if (error != NULL && error_size > 0) {
            snprintf(error, error_size, "no plan");
        }
        return NULL;
    }
    builder b = {.plan = plan, .error = error, .error_size = error_size};
    plan_cursor system_record = plan_record_values(plan, 0);
    ssx_system *sys = ssx_system_new(plan_next_text(&system_record, NULL));
    ssx_fmu **fmus = calloc(plan->n_components ? (size_t)plan->n_components : 1, sizeof *fmus);
    if (sys == NULL || fmus == NULL) {
        ssx_system_free(sys);
        free(fmus);
        build_failed(&b, "out of memory");
        return NULL;
    }
    b.sys = sys;
    sys->owned_fmus = calloc(plan->n_components ? (size_t)plan->n_components : 1,
                             sizeof *sys->owned_fmus);
    if (sys->owned_fmus == NULL) {
        free(fmus);
        ssx_system_free(sys);
        build_failed(&b, "out of memory");
        return NULL;
    }
    sys->n_owned_fmus = plan->n_components;
    int failed = 0;
    for (int k = 0; k < plan->n_components && !failed; ++k) {
        if (!is_fmu_record(plan->kind[plan->component_record[k]])) {
            continue;
        }
        if ((size_t)k < n_given && given != NULL && given[k] != NULL) {
            fmus[k] = given[k];
            continue;
        }
        fmus[k] = sys->owned_fmus[k] = load_fmu(&b, k, base_folder);
        failed = fmus[k] == NULL;
    }
    for (size_t r = 1; r < plan->n_records && !failed; ++r) {
        b.record = r;
        failed = build_record(&b, fmus) != 0;
    }
    free(fmus);
    if (failed) {
        ssx_system_free(sys);
        return NULL;
    }
    return sys;
}

/* ------------------------------------------------------------------ initializing */
typedef struct {
    const ssx_plan *plan;
    ssx_fmu *fmu;
    int component;
} text_starts;

/* Writes the String and Binary start records of one component in initialization mode. */
static int write_text_starts(void *user)
{
    const text_starts *t = user;
    const ssx_plan *p = t->plan;
    for (size_t r = 0; r < p->n_records; ++r) {
        if (p->kind[r] != PLAN_START || component_of(p, r) != t->component) {
            continue;
        }
        plan_cursor cursor = plan_record_values(p, r);
        plan_next_integer(&cursor);
        int64_t type = plan_next_integer(&cursor);
        unsigned int vr = (unsigned int)plan_next_integer(&cursor);
        if (type != SSX_STRING && type != SSX_BINARY) {
            continue;
        }
        size_t size;
        const char *text = plan_next_text(&cursor, &size);
        int status = type == SSX_STRING
                     ? ssx_fmu_set_string(t->fmu, &vr, 1, &text)
                     : ssx_fmu_set_binary(t->fmu, &vr, 1, &size,
                                          (const unsigned char *const *)&text);
        if (status != 0 && status != 1) {
            return -1;
        }
    }
    return 0;
}

/* The values one FMU is given in initialization mode, by type. */
typedef struct {
    unsigned int *vr[3];
    double *real;
    int *integer[2];
    size_t n[3];
    int texts;
} start_lists;

static void start_lists_free(start_lists *s)
{
    for (int k = 0; k < 3; ++k) {
        free(s->vr[k]);
    }
    free(s->real);
    free(s->integer[0]);
    free(s->integer[1]);
}

static void start_add(start_lists *s, int64_t type, unsigned int vr, double value)
{
    int list = type == SSX_REAL ? 0 : type == SSX_INTEGER ? 1 : 2;
    size_t k = s->n[list]++;
    s->vr[list][k] = vr;
    if (list == 0) {
        s->real[k] = value;
    } else {
        s->integer[list - 1][k] = list == 1 ? (int)value : value != 0.0;
    }
}

/* The start records of `component`, then its inputs that no connection drives, hold a
 * number (not NaN) and are not texts, in record order. */
static int start_lists_make(const ssx_plan *p, int component, const char *driven,
                            start_lists *s)
{
    size_t most = 1; /* the component's start and input records */
    for (size_t r = 0; r < p->n_records; ++r) {
        most += (p->kind[r] == PLAN_START || p->kind[r] == PLAN_INPUT) &&
                component_of(p, r) == component;
    }
    for (int k = 0; k < 3; ++k) {
        s->vr[k] = malloc(most * sizeof *s->vr[k]);
    }
    s->real = malloc(most * sizeof *s->real);
    s->integer[0] = malloc(most * sizeof(int));
    s->integer[1] = malloc(most * sizeof(int));
    if (!s->vr[0] || !s->vr[1] || !s->vr[2] || !s->real || !s->integer[0] || !s->integer[1]) {
        return -1;
    }
    for (int pass = 0; pass < 2; ++pass) {
        int input = 0;
        for (size_t r = 0; r < p->n_records; ++r) {
            int kind = pass == 0 ? PLAN_START : PLAN_INPUT;
            if (p->kind[r] != kind || component_of(p, r) != component) {
                continue;
            }
            plan_cursor cursor = plan_record_values(p, r);
            plan_next_integer(&cursor);
            int64_t type = plan_next_integer(&cursor);
            unsigned int vr = (unsigned int)plan_next_integer(&cursor);
            const plan_value *value = plan_next_value(&cursor);
            int is_driven = pass == 1 && driven[input++];
            if (type == SSX_STRING || type == SSX_BINARY) {
                s->texts |= pass == 0;
            } else if (!is_driven && !isnan(value->as.real)) {
                start_add(s, type, vr, value->as.real);
            }
        }
    }
    return 0;
}

/* The first record of Python the caller attaches (a Python component, an FMU's Python hooks, an
 * indicator function), or -1 with its component in *component. */
static int64_t python_record(const ssx_plan *plan, int *component)
{
    for (int k = 0; k < plan->n_components; ++k) {
        if (plan->kind[plan->component_record[k]] == PLAN_PYTHON) {
            *component = k;
            return (int64_t)plan->component_record[k];
        }
    }
    for (size_t r = 0; r < plan->n_records; ++r) {
        if (plan->kind[r] == PLAN_HOOKS || plan->kind[r] == PLAN_INDICATOR_CALLBACK) {
            *component = (int)plan->values[plan->first_value[r]].as.integer;
            return (int64_t)r;
        }
    }
    return -1;
}

/* The plan's components are the system's, by name, and what the build loaded are FMUs. */
static int built_from(const ssx_system *sys, const ssx_plan *plan)
{
    if (plan == NULL || plan->n_components != sys->n_components ||
        sys->n_owned_fmus != sys->n_components) {
        return 0;
    }
    for (int k = 0; k < sys->n_components; ++k) {
        size_t record = plan->component_record[k];
        plan_cursor cursor = plan_record_values(plan, record);
        if (strcmp(plan_next_text(&cursor, NULL), sys->components[k]->name) != 0 ||
            (sys->owned_fmus[k] != NULL && !is_fmu_record(plan->kind[record]))) {
            return 0;
        }
    }
    return 1;
}

int ssx_plan_initialize(ssx_system *sys, const ssx_plan *plan, double t0)
{
    if (sys == NULL) {
        return -1;
    }
    if (!built_from(sys, plan)) {
        return fail_config(sys, -1, -1, t0, "system '%s': not built from this plan", sys->name);
    }
    int python_component = -1;
    int64_t python = python_record(plan, &python_component);
    if (python >= 0) {
        return fail_config(sys, python_component, -1, t0,
                           "system '%s': component '%s' runs Python (its '%s' record), which "
                           "only Python can attach; a build without Python cannot run it",
                           sys->name, ssx_plan_component_name(plan, python_component),
                           plan_schema[plan->kind[python]].keyword);
    }
    for (int k = 0; k < sys->n_components; ++k) {
        ssx_fmu *fmu = sys->owned_fmus[k];
        if (fmu == NULL) {
            continue;
        }
        char *driven = calloc(plan->n_inputs[k] ? (size_t)plan->n_inputs[k] : 1, 1);
        if (driven == NULL) {
            return fail(sys, k, -1, t0, "out of memory");
        }
        ssx_fmu_experiment experiment = {.start_time = t0};
        for (size_t r = 0; r < plan->n_records; ++r) {
            plan_cursor cursor = plan_record_values(plan, r);
            if (plan->kind[r] == PLAN_CONNECT) {
                plan_next_integer(&cursor);
                plan_next_integer(&cursor);
                int dst = (int)plan_next_integer(&cursor);
                int input = (int)plan_next_integer(&cursor);
                if (dst == k) {
                    driven[input] = 1;
                }
            } else if (plan->kind[r] == PLAN_FMU_EXPERIMENT && component_of(plan, r) == k) {
                plan_next_integer(&cursor);
                experiment.tolerance_defined = (int)plan_next_integer(&cursor);
                experiment.tolerance = plan_next_double(&cursor);
                experiment.stop_time_defined = (int)plan_next_integer(&cursor);
                experiment.stop_time = plan_next_double(&cursor);
            }
        }
        start_lists starts = {0};
        int made = start_lists_make(plan, k, driven, &starts);
        free(driven);
        if (made != 0) {
            start_lists_free(&starts);
            return fail(sys, k, -1, t0, "out of memory");
        }
        const ssx_fmu_values values = {
            .real_vr = starts.vr[0], .real_values = starts.real, .n_real = starts.n[0],
            .integer_vr = starts.vr[1], .integer_values = starts.integer[0],
            .n_integer = starts.n[1],
            .boolean_vr = starts.vr[2], .boolean_values = starts.integer[1],
            .n_boolean = starts.n[2]};
        text_starts texts = {plan, fmu, k};
        int status = ssx_fmu_enter_initialization(fmu, &experiment, &values,
                                                  starts.texts ? write_text_starts : NULL,
                                                  &texts);
        start_lists_free(&starts);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, sys->components[k], fmu, t0, status, ssx_fmu_last_call(fmu));
        }
    }
    return ssx_initialize(sys, t0);
}

/* ------------------------------------------------------------------ what exporters read */
int ssx_plan_component_count(const ssx_plan *plan)
{
    return plan != NULL ? plan->n_components : 0;
}

const char *ssx_plan_component_name(const ssx_plan *plan, int component)
{
    if (plan == NULL || component < 0 || component >= plan->n_components) {
        return NULL;
    }
    plan_cursor cursor = plan_record_values(plan, plan->component_record[component]);
    return plan_next_text(&cursor, NULL);
}

int ssx_plan_port_count(const ssx_plan *plan, int component, int is_input)
{
    if (plan == NULL || component < 0 || component >= plan->n_components) {
        return -1;
    }
    return is_input ? plan->n_inputs[component] : plan->n_outputs[component];
}

int ssx_plan_port(const ssx_plan *plan, int component, int is_input, int port,
                  ssx_value_type *type, unsigned int *vr)
{
    if (ssx_plan_port_count(plan, component, is_input) <= port || port < 0) {
        return -1;
    }
    int seen = 0;
    for (size_t r = 0; r < plan->n_records; ++r) {
        int kind = plan->kind[r];
        int is_port = is_input ? kind == PLAN_INPUT
                               : kind == PLAN_OUTPUT || kind == PLAN_TABLE_COLUMN;
        if (!is_port || component_of(plan, r) != component || seen++ != port) {
            continue;
        }
        plan_cursor cursor = plan_record_values(plan, r);
        plan_next_integer(&cursor);
        ssx_value_type found_type = (ssx_value_type)plan_next_integer(&cursor);
        unsigned int found_vr = kind == PLAN_TABLE_COLUMN ? 0
                                : (unsigned int)plan_next_integer(&cursor);
        if (type != NULL) {
            *type = found_type;
        }
        if (vr != NULL) {
            *vr = found_vr;
        }
        return 0;
    }
    return -1;
}

int ssx_plan_experiment(const ssx_plan *plan, double *start, double *stop, double *step)
{
    for (size_t r = 0; plan != NULL && r < plan->n_records; ++r) {
        if (plan->kind[r] != PLAN_EXPERIMENT) {
            continue;
        }
        plan_cursor cursor = plan_record_values(plan, r);
        double values[3];
        for (int k = 0; k < 3; ++k) {
            values[k] = plan_next_double(&cursor);
        }
        if (start != NULL) {
            *start = values[0];
        }
        if (stop != NULL) {
            *stop = values[1];
        }
        if (step != NULL) {
            *step = values[2];
        }
        return 0;
    }
    return -1;
}
