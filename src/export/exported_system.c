/* The exported system (exported_system.h) over the engine's public API: the plan builds it,
 * ssx_step_until advances it, ssx_state_* save and restore it. */
#include "exported_system.h"

#include "export_map.h"
#include "syssimx_engine.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MESSAGE_SIZE = 2048 };
/* bounds on what the FMU's own resources may hold, as the plan reader's */
static const size_t max_plan_size = (size_t)256 << 20;
static const size_t max_map_size = (size_t)64 << 20;

/* the plan's words for an export_type */
static const char *const plan_type_words[] = {"real", "integer", "boolean"};

static const char state_magic[8] = {'S', 'S', 'X', 'E', 'X', 'P', '0', '1'};

struct exported_system {
    export_map map;
    char *plan_text;
    size_t plan_size;
    char *members;  /* the folder the member FMUs are unpacked in */
    double *values; /* by variable: what the importer set (NaN: nothing) */
    ssx_plan *plan;
    ssx_system *sys;
    double start_time; /* of initialization mode */
    int initializing;  /* in initialization mode: a parameter set builds the system again */
    long events;       /* events inside since the start: located ones and members' own */
    double last_event_time;
    int stop_at_own_events; /* steps return early at members' own events too */
    exported_log log;
    void *user;
};

struct exported_state {
    ssx_system_state *system;
    long events;
    double last_event_time;
};

static void report(const exported_system *es, const char *format, const char *detail)
{
    char message[MESSAGE_SIZE];
    snprintf(message, sizeof message, format, detail);
    es->log(es->user, 1, message);
}

static void report_engine(const exported_system *es, const char *what)
{
    const ssx_error *error = es->sys != NULL ? ssx_last_error(es->sys) : NULL;
    char message[MESSAGE_SIZE + 128];
    snprintf(message, sizeof message, "%s: %s", what,
             error != NULL && error->message[0] ? error->message : "the engine failed");
    es->log(es->user, 1, message);
}

/* The whole file at folder/name, NUL-terminated, at most limit bytes; NULL on failure. */
static char *read_file(const char *folder, const char *name, size_t limit, size_t *size,
                       char *error, size_t error_size)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    FILE *file = fopen(path, "rb");
    if (file == NULL) {
        snprintf(error, error_size, "cannot open %.1024s", path);
        return NULL;
    }
    char *text = NULL;
    long length = -1;
    if (fseek(file, 0, SEEK_END) == 0) {
        length = ftell(file);
    }
    if (length >= 0 && (size_t)length <= limit && fseek(file, 0, SEEK_SET) == 0) {
        text = malloc((size_t)length + 1);
    }
    if (text != NULL && fread(text, 1, (size_t)length, file) == (size_t)length) {
        text[length] = '\0';
        *size = (size_t)length;
    } else {
        free(text);
        text = NULL;
        snprintf(error, error_size, "cannot read %.1024s (or it is over %zu bytes)", path, limit);
    }
    fclose(file);
    return text;
}

exported_system *exported_system_new(const char *resources, const char *token, exported_log log,
                                     void *user)
{
    exported_system *es = calloc(1, sizeof *es);
    if (es == NULL) {
        log(user, 1, "out of memory");
        return NULL;
    }
    es->log = log;
    es->user = user;
    char error[MESSAGE_SIZE] = "";
    size_t map_size = 0;
    char *map_text =
        read_file(resources, "export.map", max_map_size, &map_size, error, sizeof error);
    int ok =
        map_text != NULL && export_map_read(map_text, map_size, &es->map, error, sizeof error) == 0;
    free(map_text);
    if (ok && (token == NULL || strcmp(token, es->map.token) != 0)) {
        snprintf(error, sizeof error,
                 "the token given at instantiation (%.64s) is not this "
                 "FMU's %.64s",
                 token != NULL ? token : "none", es->map.token);
        ok = 0;
    }
    if (ok) {
        es->plan_text =
            read_file(resources, "system.plan", max_plan_size, &es->plan_size, error, sizeof error);
        size_t folder_size = strlen(resources) + sizeof "/members";
        es->members = malloc(folder_size);
        es->values = malloc((es->map.n ? es->map.n : 1) * sizeof *es->values);
        ok = es->plan_text != NULL && es->members != NULL && es->values != NULL;
        if (ok) {
            snprintf(es->members, folder_size, "%s/members", resources);
        } else if (error[0] == '\0') {
            snprintf(error, sizeof error, "out of memory");
        }
    }
    if (!ok) {
        report(es, "%s", error);
        exported_system_free(es);
        return NULL;
    }
    exported_system_reset(es);
    return es;
}

static void drop_system(exported_system *es)
{
    if (es->sys != NULL) {
        ssx_system_free(es->sys);
        es->sys = NULL;
    }
    if (es->plan != NULL) {
        ssx_plan_free(es->plan);
        es->plan = NULL;
    }
    es->initializing = 0;
}

void exported_system_reset(exported_system *es)
{
    drop_system(es);
    for (size_t k = 0; k < es->map.n; k++) {
        es->values[k] = NAN;
    }
    es->events = 0;
    es->last_event_time = 0.0;
}

void exported_system_free(exported_system *es)
{
    if (es == NULL) {
        return;
    }
    drop_system(es);
    export_map_free(&es->map);
    free(es->plan_text);
    free(es->members);
    free(es->values);
    free(es);
}

/* The variable of the input `port` of `component` the importer set, or -1. */
static long input_set(const exported_system *es, int component, int port)
{
    for (size_t k = 0; k < es->map.n; k++) {
        const export_variable *v = &es->map.variables[k];
        if (v->role == EXPORT_INPUT && v->component == component && v->index == port &&
            !isnan(es->values[k])) {
            return (long)k;
        }
    }
    return -1;
}

/* The plan with what the importer set before the start: an input's value as the start of its
 * input record (the members are initialized with it, as with a value the system's own inputs
 * were given), and a start record for each parameter, written after the exporter's own, so it
 * is the one written last in initialization mode. */
static char *plan_with_importer_values(const exported_system *es, size_t *size)
{
    enum { RECORD_SIZE = 96 };
    size_t capacity = es->plan_size + 1 + es->map.n * RECORD_SIZE + 1;
    int last_component = -1; /* the last with an exported input */
    for (size_t k = 0; k < es->map.n; k++) {
        const export_variable *v = &es->map.variables[k];
        if (v->role == EXPORT_INPUT && v->component > last_component) {
            last_component = v->component;
        }
    }
    char *text = malloc(capacity);
    /* input records by component so far: a component's k-th one is its input port k */
    int *inputs_seen = calloc((size_t)last_component + 2, sizeof *inputs_seen);
    if (text == NULL || inputs_seen == NULL) {
        free(text);
        free(inputs_seen);
        return NULL;
    }
    size_t at = 0;
    for (size_t line = 0; line < es->plan_size;) {
        const char *end = memchr(es->plan_text + line, '\n', es->plan_size - line);
        const char *record = es->plan_text + line;
        size_t length = end != NULL ? (size_t)(end - record) : es->plan_size - line;
        int component = -1;
        long k = -1;
        if (length > 6 && strncmp(record, "input ", 6) == 0 &&
            sscanf(record, "input %d", &component) == 1 && component >= 0 &&
            component <= last_component) {
            k = input_set(es, component, inputs_seen[component]++);
        }
        size_t kept = length; /* with k: up to the record's last field, the input's start */
        while (k >= 0 && kept > 0 && record[kept - 1] != ' ') {
            kept--;
        }
        if (k >= 0 && kept > 0) {
            memcpy(text + at, record, kept);
            at += kept;
            at += (size_t)snprintf(text + at, capacity - at, "%.17g\n", es->values[k]);
        } else {
            memcpy(text + at, record, length);
            at += length;
            text[at++] = '\n';
        }
        line += length + 1;
    }
    free(inputs_seen);
    for (size_t k = 0; k < es->map.n; k++) {
        const export_variable *v = &es->map.variables[k];
        if (v->role == EXPORT_PARAMETER && !isnan(es->values[k])) {
            at += (size_t)snprintf(text + at, capacity - at, "start %d %s %d %.17g\n",
                                   v->component, plan_type_words[v->type], v->index, es->values[k]);
        }
    }
    *size = at;
    return text;
}

/* The inputs the importer set, into the engine's input ports. */
static void write_inputs(exported_system *es)
{
    for (size_t k = 0; k < es->map.n; k++) {
        const export_variable *v = &es->map.variables[k];
        if (v->role == EXPORT_INPUT && !isnan(es->values[k])) {
            ssx_inputs(es->sys, v->component)[v->index] = es->values[k];
        }
    }
}

int exported_system_start(exported_system *es, double t0)
{
    drop_system(es);
    char error[MESSAGE_SIZE] = "";
    size_t size = 0;
    char *text = plan_with_importer_values(es, &size);
    if (text == NULL) {
        report(es, "%s", "out of memory");
        return -1;
    }
    es->plan = ssx_plan_read(text, size, error, sizeof error);
    free(text);
    if (es->plan == NULL) {
        report(es, "the system's plan: %s", error);
        return -1;
    }
    es->sys = ssx_plan_build(es->plan, es->members, NULL, 0, error, sizeof error);
    if (es->sys == NULL) {
        report(es, "building the system: %s", error);
        drop_system(es);
        return -1;
    }
    /* an FMU keeps no history: the importer records what it wants */
    if (ssx_set_history(es->sys, 0) != 0) {
        report_engine(es, "history");
        drop_system(es);
        return -1;
    }
    ssx_set_stop_at_own_events(es->sys, es->stop_at_own_events);
    write_inputs(es);
    if (ssx_plan_initialize(es->sys, es->plan, t0) != 0) {
        report_engine(es, "initializing the system");
        drop_system(es);
        return -1;
    }
    write_inputs(es); /* ssx_initialize gives the ports their start values again */
    es->events = 0;
    es->last_event_time = t0;
    es->start_time = t0;
    es->initializing = 1;
    return 0;
}

void exported_system_stop_at_own_events(exported_system *es, int stop)
{
    es->stop_at_own_events = stop;
}

void exported_system_steps(exported_system *es)
{
    es->initializing = 0;
}

static long variable_of(const exported_system *es, unsigned int vr)
{
    long k = export_map_find(&es->map, vr);
    if (k < 0) {
        char reference[32];
        snprintf(reference, sizeof reference, "%u", vr);
        report(es, "no variable has the value reference %s", reference);
    }
    return k;
}

static const char *const type_words[] = {"a Real", "an Integer", "a Boolean"};

/* The variable of value reference vr when it is of `type`, else -1 (logged, naming it). */
static long typed_variable(const exported_system *es, unsigned int vr, export_type type)
{
    long k = variable_of(es, vr);
    if (k >= 0 && es->map.variables[k].type != type) {
        const export_variable *v = &es->map.variables[k];
        char message[MESSAGE_SIZE];
        snprintf(message, sizeof message,
                 "the variable '%.1024s' (value reference %u) is %s, not %s", v->name, vr,
                 type_words[v->type], type_words[type]);
        report(es, "%s", message);
        return -1;
    }
    return k;
}

/* Set variable k to value; *rebuild set when a parameter set in initialization mode needs
 * the members initialized again. */
static int set_value(exported_system *es, long k, double value, int *rebuild)
{
    const export_variable *v = &es->map.variables[k];
    if (v->role != EXPORT_INPUT && v->role != EXPORT_PARAMETER) {
        report(es, "'%.1024s' is an output: only inputs and parameters can be set", v->name);
        return -1;
    }
    if (v->role == EXPORT_PARAMETER && es->sys != NULL && !es->initializing) {
        report(es,
               "the parameter '%.1024s' is set before or in initialization mode (the members "
               "are initialized with it)",
               v->name);
        return -1;
    }
    es->values[k] = value;
    if (v->role == EXPORT_INPUT && es->sys != NULL) {
        ssx_inputs(es->sys, v->component)[v->index] = value;
    } else if (v->role == EXPORT_PARAMETER && es->sys != NULL) {
        *rebuild = 1;
    }
    return 0;
}

static double value_of(const exported_system *es, long k)
{
    const export_variable *v = &es->map.variables[k];
    switch (v->role) {
    case EXPORT_OUTPUT:
        return es->sys != NULL ? ssx_outputs(es->sys, v->component)[v->index] : 0.0;
    case EXPORT_INPUT:
        if (es->sys != NULL) {
            return ssx_inputs(es->sys, v->component)[v->index];
        }
        return isnan(es->values[k]) ? v->start : es->values[k];
    case EXPORT_PARAMETER:
        return isnan(es->values[k]) ? v->start : es->values[k];
    case EXPORT_LAST_EVENT_TIME:
        return es->last_event_time;
    case EXPORT_EVENTS:
        break;
    }
    return es->events < INT32_MAX ? (double)es->events : (double)INT32_MAX;
}

int exported_system_set_real(exported_system *es, const unsigned int *vr, size_t n,
                             const double *values)
{
    int rebuild = 0;
    for (size_t i = 0; i < n; i++) {
        long k = typed_variable(es, vr[i], EXPORT_REAL);
        if (k < 0 || set_value(es, k, values[i], &rebuild) != 0) {
            return -1;
        }
    }
    /* in initialization mode: the members are initialized again with the parameters */
    return rebuild ? exported_system_start(es, es->start_time) : 0;
}

int exported_system_set_integer(exported_system *es, const unsigned int *vr, size_t n,
                                const int *values, int boolean)
{
    int rebuild = 0;
    for (size_t i = 0; i < n; i++) {
        long k = typed_variable(es, vr[i], boolean ? EXPORT_BOOLEAN : EXPORT_INTEGER);
        double value = boolean ? (values[i] != 0) : (double)values[i];
        if (k < 0 || set_value(es, k, value, &rebuild) != 0) {
            return -1;
        }
    }
    return rebuild ? exported_system_start(es, es->start_time) : 0;
}

int exported_system_get_real(exported_system *es, const unsigned int *vr, size_t n, double *values)
{
    for (size_t i = 0; i < n; i++) {
        long k = typed_variable(es, vr[i], EXPORT_REAL);
        if (k < 0) {
            return -1;
        }
        values[i] = value_of(es, k);
    }
    return 0;
}

int exported_system_get_integer(exported_system *es, const unsigned int *vr, size_t n, int *values,
                                int boolean)
{
    for (size_t i = 0; i < n; i++) {
        long k = typed_variable(es, vr[i], boolean ? EXPORT_BOOLEAN : EXPORT_INTEGER);
        if (k < 0) {
            return -1;
        }
        double value = value_of(es, k);
        /* the engine holds an Integer or Boolean port as a double of that value */
        values[i] = boolean ? value != 0.0 : isnan(value) ? 0 : (int)value;
    }
    return 0;
}

/* The event instants the indicators made and the events members handled in their own steps
 * (an FMI 3.0 member's early return, a Model Exchange member's state or time event): an own
 * event's handlers run inside the FMU as a located event's do. */
static long events_handled(const ssx_system *sys)
{
    ssx_statistics statistics;
    ssx_get_statistics(sys, &statistics);
    return statistics.events + statistics.own_events;
}

/* The time of the latest event record, `otherwise` when there is none. */
static double latest_event_time(const ssx_system *sys, double otherwise)
{
    size_t count = ssx_event_count(sys);
    ssx_event_record record;
    return count > 0 && ssx_event_get(sys, count - 1, &record) == 0 ? record.t : otherwise;
}

int exported_system_step(exported_system *es, double t, double h, int may_return_early,
                         double *reached, int *returned_early)
{
    *returned_early = 0;
    *reached = t;
    if (es->sys == NULL) {
        report(es, "%s", "a step before initialization");
        return -1;
    }
    double now = ssx_time(es->sys);
    /* an importer's times are its own sums (libcosim's whole nanoseconds, FMPy's additions):
     * a communication point within 1e-9 steps of the system's time is that time */
    if (!(fabs(t - now) <= 1e-9 * h)) {
        char times[96];
        snprintf(times, sizeof times, "%.17g (the system is at %.17g)", t, now);
        report(es, "a step from %s: steps go on from where the last one ended", times);
        return -1;
    }
    double t_stop = t + h;
    double dt = es->map.step > 0.0 ? es->map.step : h;
    for (;;) {
        long before = events_handled(es->sys);
        ssx_step_outcome outcome;
        if (ssx_step_until(es->sys, t_stop, dt, &outcome) != 0) {
            report_engine(es, "the system's step");
            return -1;
        }
        *reached = outcome.time;
        long handled = events_handled(es->sys) - before;
        if (handled > 0) {
            es->events += handled;
            es->last_event_time = latest_event_time(es->sys, outcome.time);
        }
        if (outcome.terminated) {
            return 1;
        }
        if (!outcome.event) {
            return 0;
        }
        if (may_return_early) {
            *returned_early = 1;
            return 0;
        }
    }
}

double exported_system_time(const exported_system *es)
{
    return es->sys != NULL ? ssx_time(es->sys) : 0.0;
}

exported_state *exported_state_save(exported_system *es)
{
    exported_state *state = calloc(1, sizeof *state);
    if (state == NULL || es->sys == NULL) {
        report(es, "%s", state == NULL ? "out of memory" : "no state before initialization");
        free(state);
        return NULL;
    }
    state->system = ssx_state_save(es->sys);
    if (state->system == NULL) {
        report_engine(es, "saving the system's state");
        free(state);
        return NULL;
    }
    state->events = es->events;
    state->last_event_time = es->last_event_time;
    return state;
}

int exported_state_restore(exported_system *es, const exported_state *state)
{
    if (es->sys == NULL || ssx_state_restore(es->sys, state->system) != 0) {
        report_engine(es, "restoring the system's state");
        return -1;
    }
    es->events = state->events;
    es->last_event_time = state->last_event_time;
    return 0;
}

void exported_state_free(exported_state *state)
{
    if (state != NULL) {
        ssx_state_free(state->system);
        free(state);
    }
}

/* The serialized state: magic, the event count (int64) and the last event's time (double) in
 * this machine's byte order, then the engine's bytes (which check the system they belong to). */
enum { HEADER_SIZE = sizeof state_magic + sizeof(int64_t) + sizeof(double) };

unsigned char *exported_state_serialize(exported_system *es, const exported_state *state,
                                        size_t *size)
{
    unsigned char *system_bytes = NULL;
    size_t system_size = 0;
    if (es->sys == NULL ||
        ssx_state_serialize(es->sys, state->system, &system_bytes, &system_size) != 0) {
        report_engine(es, "serializing the system's state");
        return NULL;
    }
    unsigned char *bytes = malloc(HEADER_SIZE + system_size);
    if (bytes != NULL) {
        int64_t events = state->events;
        memcpy(bytes, state_magic, sizeof state_magic);
        memcpy(bytes + sizeof state_magic, &events, sizeof events);
        memcpy(bytes + sizeof state_magic + sizeof events, &state->last_event_time,
               sizeof state->last_event_time);
        memcpy(bytes + HEADER_SIZE, system_bytes, system_size);
        *size = HEADER_SIZE + system_size;
    } else {
        report(es, "%s", "out of memory");
    }
    free(system_bytes);
    return bytes;
}

exported_state *exported_state_deserialize(exported_system *es, const unsigned char *bytes,
                                           size_t size)
{
    if (es->sys == NULL || size < HEADER_SIZE ||
        memcmp(bytes, state_magic, sizeof state_magic) != 0) {
        report(es, "%s", "the bytes are no serialized state of this exported FMU");
        return NULL;
    }
    exported_state *state = calloc(1, sizeof *state);
    if (state == NULL) {
        report(es, "%s", "out of memory");
        return NULL;
    }
    int64_t events;
    memcpy(&events, bytes + sizeof state_magic, sizeof events);
    memcpy(&state->last_event_time, bytes + sizeof state_magic + sizeof events,
           sizeof state->last_event_time);
    state->events = (long)events;
    state->system = ssx_state_deserialize(es->sys, bytes + HEADER_SIZE, size - HEADER_SIZE);
    if (state->system == NULL) {
        report_engine(es, "deserializing the system's state");
        free(state);
        return NULL;
    }
    return state;
}
