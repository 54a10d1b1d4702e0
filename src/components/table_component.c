/* A table source: each output is a column of a time table, evaluated in C at the times the
 * engine asks for, so an input signal costs no Python per step.
 *
 * The value at a time follows FMPy's Input class (simulate_fmu(input=...)), so a table fed to an
 * FMU gives FMPy's numbers: the first row before the table and the last row after it, linear
 * interpolation or hold of the row on the left inside it, and at a repeated time stamp (a
 * discontinuity) the value on the right of the jump once the run has started. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "component.h"
#include "component_setup.h"
#include "error.h"
#include "system.h"

typedef struct {
    double *time;   /* n_rows, non-decreasing */
    size_t n_rows;
    double *values; /* column after column, n_rows each */
    int *hold;      /* per column: 1 holds the row on the left, 0 interpolates linearly */
    int n_columns;
} ssx_table;

/* Python's math.isclose with its defaults (relative 1e-9): FMPy's test for "the same time". */
static int is_close(double a, double b)
{
    return a == b || fabs(a - b) <= 1e-9 * fmax(fabs(a), fabs(b));
}

/* The first row whose time is >= time (n_rows when there is none). */
static size_t first_row_at_or_after(const ssx_table *table, double time)
{
    size_t low = 0, high = table->n_rows;
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        if (table->time[middle] < time) {
            low = middle + 1;
        } else {
            high = middle;
        }
    }
    return low;
}

/* after_event: at a discontinuity take the value on its right (every step of a run does);
 * before the run starts the value on its left is taken. */
static double column_value(const ssx_table *table, int column, double time, int after_event)
{
    const double *t = table->time;
    const double *v = table->values + (size_t)column * table->n_rows;
    size_t n = table->n_rows;
    if (n < 2) {
        return v[0];
    }
    size_t i = first_row_at_or_after(table, time);
    if (i == 0) {
        return v[0];
    }
    if (i == n) {
        return v[n - 1];
    }
    if (table->hold[column]) {
        size_t left = i - 1;
        while (after_event && left + 1 < n && (t[left + 1] < time || is_close(time, t[left + 1]))) {
            left++;
        }
        return v[left];
    }
    if (is_close(time, t[i]) && i + 1 < n && is_close(t[i], t[i + 1])) {
        while (after_event && i + 1 < n && is_close(t[i], t[i + 1])) {
            i++;
        }
        return v[i];
    }
    /* the same arithmetic as FMPy, so equal tables give equal bits */
    double w_left = (t[i] - time) / (t[i] - t[i - 1]);
    double w_right = 1.0 - w_left;
    return w_left * v[i - 1] + w_right * v[i];
}

static void table_values(const ssx_table *table, double time, int after_event, double *values)
{
    for (int k = 0; k < table->n_columns; ++k) {
        values[k] = column_value(table, k, time, after_event);
    }
}

static void evaluate(ssx_component *c, double time, int after_event)
{
    table_values(c->data, time, after_event, c->outputs);
}

static int table_do_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    (void)sys;
    evaluate(c, t + dt, 1);
    return 0;
}

static int table_ports_in_place(ssx_system *sys, ssx_component *c)
{
    (void)sys;
    (void)c;
    return 0; /* no inputs, and the outputs are written where the engine reads them */
}

static int table_evaluate_outputs(ssx_system *sys, ssx_component *c, double t)
{
    /* While the system initializes the run has not started: the left value of a jump at t0. */
    evaluate(c, t, sys->initialized);
    return 0;
}

static int table_snapshot(ssx_system *sys, ssx_component *c, int slot)
{
    (void)sys;
    (void)c;
    (void)slot;
    return 0; /* no state: the engine saves and restores the outputs of every component */
}

static int table_restore(ssx_system *sys, ssx_component *c, int slot, double t)
{
    (void)sys;
    (void)c;
    (void)slot;
    (void)t;
    return 0;
}

static void table_free(ssx_table *table)
{
    if (table != NULL) {
        free(table->time);
        free(table->values);
        free(table->hold);
        free(table);
    }
}

static void table_release(ssx_component *c)
{
    table_free(c->data);
    c->data = NULL;
}

/* A function of time: restoring its outputs restores it. */
static int table_can_roll_back(const ssx_component *c)
{
    (void)c;
    return 1;
}

const ssx_component_ops ssx_table_component_ops = {
    .do_step = table_do_step,
    .write_inputs = table_ports_in_place,
    .read_outputs = table_ports_in_place,
    .evaluate_outputs = table_evaluate_outputs,
    .snapshot = table_snapshot,
    .restore = table_restore,
    .saved_state = &component_no_saved_state,
    .release = table_release,
    .can_roll_back = table_can_roll_back,
};

int ssx_add_table_component(ssx_system *sys, const char *name, const double *time, size_t n_rows)
{
    const char *label = name != NULL ? name : "?";
    if (time == NULL || n_rows == 0) {
        return fail_config(sys, -1, -1, NAN, "table '%s': the table has no rows", label);
    }
    for (size_t row = 0; row < n_rows; ++row) {
        if (!isfinite(time[row])) {
            return fail_config(sys, -1, -1, NAN,
                               "table '%s': the time in row %zu is %g, not a finite "
                               "number",
                               label, row, time[row]);
        }
        if (row > 0 && time[row] < time[row - 1]) {
            return fail_config(sys, -1, -1, NAN,
                               "table '%s': the time goes back from %.17g to %.17g in "
                               "row %zu; times must not decrease",
                               label, time[row - 1], time[row], row);
        }
    }
    ssx_table *table = calloc(1, sizeof *table);
    if (table == NULL || (table->time = malloc(n_rows * sizeof *table->time)) == NULL) {
        table_free(table);
        return fail_config(sys, -1, -1, NAN, "out of memory adding table '%s'", label);
    }
    memcpy(table->time, time, n_rows * sizeof *table->time);
    table->n_rows = n_rows;
    int index = system_add_component(sys, name, 1, &ssx_table_component_ops, 0);
    if (index < 0) {
        table_free(table);
        return -1;
    }
    sys->components[index]->data = table;
    return index;
}

int ssx_add_table_column(ssx_system *sys, int component, ssx_value_type type, int hold,
                         const double *values)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    ssx_table *table = c->data;
    if (c->ops != &ssx_table_component_ops || table->n_columns != c->n_outputs) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s' is not a table source of its own "
                           "columns",
                           c->name);
    }
    for (size_t row = 0; row < table->n_rows; ++row) {
        if (!isfinite(values[row])) {
            return fail_config(sys, component, -1, NAN,
                               "table '%s': column %d holds %g in row %zu; "
                               "values must be finite",
                               c->name, table->n_columns, values[row], row);
        }
    }
    size_t n = table->n_rows;
    size_t columns = (size_t)table->n_columns + 1;
    double *grown = realloc(table->values, columns * n * sizeof *grown);
    if (grown != NULL) {
        table->values = grown;
    }
    int *holds = realloc(table->hold, columns * sizeof *holds);
    if (holds != NULL) {
        table->hold = holds;
    }
    if (grown == NULL || holds == NULL) {
        return fail_config(sys, component, -1, NAN, "out of memory adding a column to table '%s'",
                           c->name);
    }
    int output = ssx_add_output(sys, component, type, 0);
    if (output < 0) {
        return -1;
    }
    memcpy(table->values + (size_t)table->n_columns * n, values, n * sizeof *values);
    /* integers and booleans only change at rows, as FMPy holds every discrete input */
    table->hold[table->n_columns] = hold || type != SSX_REAL;
    table->n_columns++;
    return output;
}

int ssx_table_values(ssx_system *sys, int component, double t, int after_event, double *values)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (c->ops != &ssx_table_component_ops) {
        return fail_config(sys, component, -1, t, "component '%s' is not a table source", c->name);
    }
    table_values(c->data, t, after_event, values);
    return 0;
}
