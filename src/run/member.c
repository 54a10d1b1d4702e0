/* Members of an ensemble run by the engine: the system initialized once, each member its FMU
 * components started again from their start values with the member's parameter values written
 * over some of them, then initialized and run, without a call into the caller per component.
 * What a member writes is what the caller's own initialize writes for the same parameters:
 * the start values are the caller's, the member's values go into their slots among them (and
 * among a restart handler's start values), so the FMUs see the same calls in the same order. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "fmu_component.h"
#include "restart_handler.h"
#include "system.h"

/* A component's start values as the caller set them, by type (owned copies). */
typedef struct {
    int set;
    ssx_fmu_experiment experiment;
    unsigned int *vr[3];
    double *real;
    int *discrete[2]; /* Integer, Boolean: [type - SSX_INTEGER] */
    size_t n[3];
} member_start;

typedef struct {
    int component;
    ssx_value_type type;
    unsigned int vr;
    int restart; /* also a start value of the component's restart handler */
    size_t slot; /* its place among the component's start values of its type */
} member_column;

/* The samples of the members of the last ssx_run_members, one member after another: per
 * sample a row of the time and every component's outputs (in component order). */
typedef struct {
    double *rows;
    int *micro;
    size_t n_rows;
    size_t capacity; /* rows */
    size_t width;
    size_t *bounds; /* members + 1 row offsets */
    size_t n_members;
} member_samples;

struct ssx_members {
    ssx_system *sys;
    member_column *columns;
    size_t n_columns;
    member_start *starts; /* per component */
    int n_components;
    member_samples samples;
};

static void start_free(member_start *s)
{
    for (int type = 0; type < 3; ++type) {
        free(s->vr[type]);
    }
    free(s->real);
    free(s->discrete[0]);
    free(s->discrete[1]);
    memset(s, 0, sizeof *s);
}

void ssx_members_free(ssx_members *m)
{
    if (m == NULL) {
        return;
    }
    for (int i = 0; i < m->n_components; ++i) {
        start_free(&m->starts[i]);
    }
    free(m->starts);
    free(m->columns);
    free(m->samples.rows);
    free(m->samples.micro);
    free(m->samples.bounds);
    free(m);
}

ssx_members *ssx_members_new(ssx_system *sys, size_t n_columns, const int *component,
                             const int *type, const unsigned int *vr, const int *restart)
{
    if (sys == NULL) {
        return NULL;
    }
    for (size_t k = 0; k < n_columns; ++k) {
        if (system_component(sys, component[k]) == NULL) {
            return NULL;
        }
        if (type[k] != SSX_REAL && type[k] != SSX_INTEGER && type[k] != SSX_BOOLEAN) {
            fail_config(sys, component[k], -1, NAN,
                        "member column %zu: a member writes Real, Integer or Boolean values, "
                        "not type %d", k, type[k]);
            return NULL;
        }
    }
    ssx_members *m = calloc(1, sizeof *m);
    if (m != NULL) {
        m->sys = sys;
        m->n_components = sys->n_components;
        m->n_columns = n_columns;
        m->columns = calloc(n_columns > 0 ? n_columns : 1, sizeof *m->columns);
        m->starts = calloc(sys->n_components > 0 ? (size_t)sys->n_components : 1,
                           sizeof *m->starts);
    }
    if (m == NULL || m->columns == NULL || m->starts == NULL) {
        ssx_members_free(m);
        fail_config(sys, -1, -1, NAN, "out of memory preparing the members");
        return NULL;
    }
    for (size_t k = 0; k < n_columns; ++k) {
        m->columns[k] = (member_column){.component = component[k],
                                        .type = (ssx_value_type)type[k],
                                        .vr = vr[k],
                                        .restart = restart[k] != 0};
    }
    return m;
}

static void *copy(const void *from, size_t n, size_t size)
{
    void *to = malloc(n > 0 ? n * size : 1);
    if (to != NULL && n > 0) {
        memcpy(to, from, n * size);
    }
    return to;
}

/* Where vr is among s's start values of its type, or -1. */
static long slot_of(const member_start *s, ssx_value_type type, unsigned int vr)
{
    for (size_t j = 0; j < s->n[type]; ++j) {
        if (s->vr[type][j] == vr) {
            return (long)j;
        }
    }
    return -1;
}

int ssx_members_set_start(ssx_members *m, int component, const ssx_fmu_experiment *experiment,
                          const ssx_fmu_values *starts)
{
    ssx_system *sys = m->sys;
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (fmu_component_binding(c) == NULL || experiment == NULL) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s': a member starts FMU components only, with an "
                           "experiment", c->name);
    }
    member_start *s = &m->starts[component];
    start_free(s);
    ssx_fmu_values none = {0};
    const ssx_fmu_values *v = starts != NULL ? starts : &none;
    s->experiment = *experiment;
    s->n[SSX_REAL] = v->n_real;
    s->n[SSX_INTEGER] = v->n_integer;
    s->n[SSX_BOOLEAN] = v->n_boolean;
    s->vr[SSX_REAL] = copy(v->real_vr, v->n_real, sizeof(unsigned int));
    s->vr[SSX_INTEGER] = copy(v->integer_vr, v->n_integer, sizeof(unsigned int));
    s->vr[SSX_BOOLEAN] = copy(v->boolean_vr, v->n_boolean, sizeof(unsigned int));
    s->real = copy(v->real_values, v->n_real, sizeof(double));
    s->discrete[0] = copy(v->integer_values, v->n_integer, sizeof(int));
    s->discrete[1] = copy(v->boolean_values, v->n_boolean, sizeof(int));
    if (s->vr[0] == NULL || s->vr[1] == NULL || s->vr[2] == NULL || s->real == NULL ||
        s->discrete[0] == NULL || s->discrete[1] == NULL) {
        start_free(s);
        return fail_config(sys, component, -1, NAN, "out of memory keeping the start values "
                           "of '%s'", c->name);
    }
    for (size_t k = 0; k < m->n_columns; ++k) {
        member_column *column = &m->columns[k];
        if (column->component != component) {
            continue;
        }
        long slot = slot_of(s, column->type, column->vr);
        if (slot < 0) {
            start_free(s);
            return fail_config(sys, component, -1, NAN,
                               "component '%s': member column %zu (value reference %u) is not "
                               "among its start values", c->name, k, column->vr);
        }
        column->slot = (size_t)slot;
    }
    s->set = 1;
    return 0;
}

/* The member's values into the start values (and the restart handlers' start values). */
static int write_columns(ssx_members *m, const double *values)
{
    for (size_t k = 0; k < m->n_columns; ++k) {
        const member_column *column = &m->columns[k];
        member_start *s = &m->starts[column->component];
        double value = values[k];
        if (column->type == SSX_REAL) {
            s->real[column->slot] = value;
        } else {
            s->discrete[column->type - SSX_INTEGER][column->slot] =
                column->type == SSX_BOOLEAN ? value != 0.0 : (int)value;
        }
        if (column->restart) {
            ssx_component *c = m->sys->components[column->component];
            ssx_restart *r = fmu_data(c)->restart;
            if (r == NULL || restart_set_start(r, column->type, column->vr, value) != 0) {
                return fail_config(m->sys, column->component, -1, NAN,
                                   "component '%s': member column %zu (value reference %u) is "
                                   "not among its restart's start values", c->name, k,
                                   column->vr);
            }
        }
    }
    return 0;
}

/* Every FMU component reset to its start values at t0, left in initialization mode for
 * ssx_initialize, in component order (the order of the caller's own initialize); every input
 * holds its start value again, as ssx_reset_inputs leaves it before such an initialize. */
static int start_components(ssx_members *m, double t0)
{
    ssx_system *sys = m->sys;
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        for (int k = 0; k < c->n_inputs; ++k) {
            c->inputs[k] = c->input_starts[k];
        }
        ssx_fmu *fmu = fmu_component_binding(c);
        member_start *s = i < m->n_components ? &m->starts[i] : NULL;
        if (fmu == NULL || s == NULL || !s->set) {
            return fail_config(sys, i, -1, t0,
                               "component '%s': a member starts FMU components only, each "
                               "given its start values (ssx_members_set_start)", c->name);
        }
        ssx_fmu_values starts = {
            .real_vr = s->vr[SSX_REAL], .real_values = s->real, .n_real = s->n[SSX_REAL],
            .integer_vr = s->vr[SSX_INTEGER], .integer_values = s->discrete[0],
            .n_integer = s->n[SSX_INTEGER], .boolean_vr = s->vr[SSX_BOOLEAN],
            .boolean_values = s->discrete[1], .n_boolean = s->n[SSX_BOOLEAN]};
        s->experiment.start_time = t0;
        int status = ssx_fmu_enter_initialization(fmu, &s->experiment, &starts, NULL, NULL);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, fmu, t0, status, ssx_fmu_last_call(fmu));
        }
    }
    return 0;
}

int ssx_run_member(ssx_members *m, const double *values, double t0, double tf, double dt)
{
    if (m == NULL || (values == NULL && m->n_columns > 0)) {
        return -1;
    }
    clear_error(m->sys);
    if (m->n_components != m->sys->n_components) {
        return fail_config(m->sys, -1, -1, t0, "system '%s': components were added after its "
                           "members were prepared", m->sys->name);
    }
    if (write_columns(m, values) != 0 || start_components(m, t0) != 0 ||
        ssx_initialize(m->sys, t0) != 0) {
        return -1;
    }
    return ssx_run(m->sys, t0, tf, dt);
}

/* Room for `more` rows after the ones kept; 0, or -1 with the error set. */
static int grow_rows(ssx_members *m, size_t more)
{
    member_samples *out = &m->samples;
    if (out->n_rows + more <= out->capacity) {
        return 0;
    }
    size_t capacity = out->capacity > 0 ? out->capacity : 256;
    while (capacity < out->n_rows + more) {
        capacity *= 2;
    }
    double *rows = realloc(out->rows, capacity * out->width * sizeof *rows);
    if (rows != NULL) {
        out->rows = rows;
    }
    int *micro = realloc(out->micro, capacity * sizeof *micro);
    if (micro != NULL) {
        out->micro = micro;
    }
    if (rows == NULL || micro == NULL) {
        return fail_config(m->sys, -1, -1, NAN, "out of memory keeping the members' samples");
    }
    out->capacity = capacity;
    return 0;
}

/* The history of the member just run, appended as rows. */
static int keep_samples(ssx_members *m)
{
    ssx_system *sys = m->sys;
    member_samples *out = &m->samples;
    size_t length = ssx_history_length(sys);
    if (grow_rows(m, length) != 0) {
        return -1;
    }
    const double *time = ssx_history_time(sys);
    const int *micro = ssx_history_micro(sys);
    double *row = out->rows + out->n_rows * out->width;
    for (size_t j = 0; j < length; ++j) {
        row[j * out->width] = time[j];
    }
    size_t column = 1;
    for (int i = 0; i < sys->n_components; ++i) {
        size_t n_outputs = (size_t)sys->components[i]->n_outputs;
        const double *values = ssx_history_values(sys, i);
        for (size_t j = 0; j < length && n_outputs > 0; ++j) {
            memcpy(row + j * out->width + column, values + j * n_outputs,
                   n_outputs * sizeof *values);
        }
        column += n_outputs;
    }
    memcpy(out->micro + out->n_rows, micro, length * sizeof *micro);
    out->n_rows += length;
    out->bounds[++out->n_members] = out->n_rows;
    return 0;
}

int ssx_run_members(ssx_members *m, size_t n, const double *values, double t0, double tf,
                    double dt)
{
    if (m == NULL || (values == NULL && n > 0 && m->n_columns > 0)) {
        return -1;
    }
    member_samples *out = &m->samples;
    size_t width = 1;
    for (int i = 0; i < m->sys->n_components; ++i) {
        width += (size_t)m->sys->components[i]->n_outputs;
    }
    if (width != out->width) { /* rows of another width: kept ones are of no use */
        free(out->rows);
        free(out->micro);
        out->rows = NULL;
        out->micro = NULL;
        out->capacity = 0;
        out->width = width;
    }
    size_t *bounds = realloc(out->bounds, (n + 1) * sizeof *bounds);
    if (bounds == NULL) {
        return fail_config(m->sys, -1, -1, NAN, "out of memory keeping the members' samples");
    }
    out->bounds = bounds;
    out->bounds[0] = 0;
    out->n_rows = 0;
    out->n_members = 0;
    int status = 0;
    monitor_batch_start(&m->sys->monitor);
    for (size_t k = 0; k < n && status == 0; ++k) {
        status = ssx_run_member(m, values + k * m->n_columns, t0, tf, dt) != 0 ||
                         keep_samples(m) != 0
                     ? -1
                     : 0;
    }
    monitor_batch_end(&m->sys->monitor);
    return status;
}

size_t ssx_members_samples(const ssx_members *m, const double **rows, const int **micro,
                           const size_t **bounds, size_t *width)
{
    *rows = m->samples.rows;
    *micro = m->samples.micro;
    *bounds = m->samples.bounds;
    *width = m->samples.width;
    return m->samples.n_members;
}
