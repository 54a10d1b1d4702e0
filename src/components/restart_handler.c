/* The restart of an FMU component at an event, as ssx_set_restart_handler describes it. The
 * start values are copied when the handler is set; the values taken from the outputs and the
 * inputs are written inside initialization mode, after them, so they win over a start value of
 * the same variable. */
#include "restart_handler.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "fmu_backend.h"
#include "fmu_binding.h"

struct ssx_restart {
    ssx_fmu_experiment experiment;
    /* the start values, owned copies */
    unsigned int *vr[3];
    double *real_values;
    int *int_values[2]; /* Integer, Boolean */
    size_t n[3];
    /* the values from the outputs: vr[k] = scale[k] * outputs[source[k]] + offset[k] */
    unsigned int *target;
    int *source;
    double *scale;
    double *offset;
    double *values;
    size_t n_targets;
    /* the inputs holding a value at the event, by type, gathered there */
    unsigned int *input_vr;
    double *input_real;
    int *input_int;
};

void restart_free(ssx_restart *r)
{
    if (r == NULL) {
        return;
    }
    for (int k = 0; k < 3; ++k) {
        free(r->vr[k]);
    }
    free(r->real_values);
    free(r->int_values[0]);
    free(r->int_values[1]);
    free(r->target);
    free(r->source);
    free(r->scale);
    free(r->offset);
    free(r->values);
    free(r->input_vr);
    free(r->input_real);
    free(r->input_int);
    free(r);
}

static void *copy(const void *from, size_t n, size_t size)
{
    void *to = malloc(n > 0 ? n * size : 1);
    if (to != NULL && n > 0) {
        memcpy(to, from, n * size);
    }
    return to;
}

typedef struct {
    ssx_system *sys;
    ssx_component *c;
    ssx_fmu *fmu;
    ssx_restart *r;
    double t;
    int status;        /* the failing call's status */
    const char *call;  /* and its name, NULL when none failed */
} restart_work;

static int wrote(restart_work *w, int status, ssx_fmu_slot slot)
{
    if (fmi_ok(status)) {
        return 1;
    }
    w->status = status;
    w->call = ssx_fmu_function_name(w->fmu, (int)slot);
    return 0;
}

/* The inputs holding a value (NaN: the FMU keeps its own), one write per type. */
static int write_inputs(restart_work *w)
{
    ssx_component *c = w->c;
    ssx_fmu *fmu = w->fmu;
    ssx_restart *r = w->r;
    static const ssx_fmu_slot slots[3] = {SLOT_SET_REAL, SLOT_SET_INTEGER, SLOT_SET_BOOLEAN};
    for (int type = 0; type < 3; ++type) {
        size_t n = 0;
        for (int k = 0; k < c->n_inputs; ++k) {
            if ((int)c->input_ports[k].type != type || isnan(c->inputs[k])) {
                continue;
            }
            r->input_vr[n] = c->input_ports[k].vr;
            if (type == SSX_REAL) {
                r->input_real[n] = c->inputs[k];
            } else {
                r->input_int[n] =
                    type == SSX_BOOLEAN ? c->inputs[k] != 0.0 : (int)lround(c->inputs[k]);
            }
            ++n;
        }
        if (n == 0) {
            continue;
        }
        int status = type == SSX_REAL ? ssx_fmu_set_real(fmu, r->input_vr, n, r->input_real)
                     : type == SSX_INTEGER
                         ? ssx_fmu_set_integer(fmu, r->input_vr, n, r->input_int)
                         : ssx_fmu_set_boolean(fmu, r->input_vr, n, r->input_int);
        if (!wrote(w, status, slots[type])) {
            return -1;
        }
    }
    return 0;
}

static int in_initialization_mode(void *user)
{
    restart_work *w = user;
    ssx_restart *r = w->r;
    if (r->n_targets > 0 && !wrote(w, ssx_fmu_set_real(w->fmu, r->target, r->n_targets,
                                                       r->values),
                                   SLOT_SET_REAL)) {
        return -1;
    }
    return write_inputs(w);
}

int restart_handle(ssx_system *sys, ssx_component *c, ssx_fmu *fmu, ssx_restart *r, double t)
{
    for (size_t k = 0; k < r->n_targets; ++k) {
        r->values[k] = r->scale[k] * c->outputs[r->source[k]] + r->offset[k];
    }
    ssx_fmu_values starts = {
        .real_vr = r->vr[SSX_REAL], .real_values = r->real_values, .n_real = r->n[SSX_REAL],
        .integer_vr = r->vr[SSX_INTEGER], .integer_values = r->int_values[0],
        .n_integer = r->n[SSX_INTEGER], .boolean_vr = r->vr[SSX_BOOLEAN],
        .boolean_values = r->int_values[1], .n_boolean = r->n[SSX_BOOLEAN]};
    r->experiment.start_time = t;
    restart_work w = {.sys = sys, .c = c, .fmu = fmu, .r = r, .t = t};
    int status = ssx_fmu_initialize(fmu, &r->experiment, &starts, in_initialization_mode, &w);
    if (!fmi_ok(status)) {
        if (w.call != NULL) {
            return fail_fmi(sys, c, fmu, t, w.status, w.call);
        }
        return fail_fmi(sys, c, fmu, t, status, ssx_fmu_last_call(fmu));
    }
    return 0;
}

int restart_set_start(ssx_restart *r, ssx_value_type type, unsigned int vr, double value)
{
    for (size_t k = 0; k < r->n[type]; ++k) {
        if (r->vr[type][k] != vr) {
            continue;
        }
        if (type == SSX_REAL) {
            r->real_values[k] = value;
        } else {
            r->int_values[type - SSX_INTEGER][k] = type == SSX_BOOLEAN ? value != 0.0 : (int)value;
        }
        return 0;
    }
    return -1;
}

ssx_restart *restart_new(ssx_system *sys, const ssx_component *c,
                         const ssx_fmu_experiment *experiment, const ssx_fmu_values *starts,
                         const unsigned int *vr, const int *source, const double *scale,
                         const double *offset, size_t n)
{
    ssx_restart *r = calloc(1, sizeof *r);
    ssx_fmu_values none = {0};
    const ssx_fmu_values *s = starts != NULL ? starts : &none;
    size_t inputs = (size_t)c->n_inputs;
    if (r != NULL) {
        r->experiment = *experiment;
        r->n[SSX_REAL] = s->n_real;
        r->n[SSX_INTEGER] = s->n_integer;
        r->n[SSX_BOOLEAN] = s->n_boolean;
        r->vr[SSX_REAL] = copy(s->real_vr, s->n_real, sizeof(unsigned int));
        r->vr[SSX_INTEGER] = copy(s->integer_vr, s->n_integer, sizeof(unsigned int));
        r->vr[SSX_BOOLEAN] = copy(s->boolean_vr, s->n_boolean, sizeof(unsigned int));
        r->real_values = copy(s->real_values, s->n_real, sizeof(double));
        r->int_values[0] = copy(s->integer_values, s->n_integer, sizeof(int));
        r->int_values[1] = copy(s->boolean_values, s->n_boolean, sizeof(int));
        r->target = copy(vr, n, sizeof(unsigned int));
        r->source = copy(source, n, sizeof(int));
        r->scale = copy(scale, n, sizeof(double));
        r->offset = copy(offset, n, sizeof(double));
        r->values = malloc(n > 0 ? n * sizeof(double) : 1);
        r->n_targets = n;
        r->input_vr = malloc(inputs > 0 ? inputs * sizeof(unsigned int) : 1);
        r->input_real = malloc(inputs > 0 ? inputs * sizeof(double) : 1);
        r->input_int = malloc(inputs > 0 ? inputs * sizeof(int) : 1);
    }
    if (r == NULL || r->vr[0] == NULL || r->vr[1] == NULL || r->vr[2] == NULL ||
        r->real_values == NULL || r->int_values[0] == NULL || r->int_values[1] == NULL ||
        r->target == NULL || r->source == NULL || r->scale == NULL || r->offset == NULL ||
        r->values == NULL || r->input_vr == NULL || r->input_real == NULL ||
        r->input_int == NULL) {
        restart_free(r);
        fail_config(sys, c->index, -1, NAN, "out of memory setting the restart of '%s'",
                    c->name);
        return NULL;
    }
    return r;
}
