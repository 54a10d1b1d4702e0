/* An FMI 3.0 Scheduled Execution FMU as a component: it has no step of its own, so each
 * communication step from t to t + h activates, in time order, the model partitions of the input
 * clocks that tick in [t, t + h) (a tick within the grid's rounding of t + h belongs to the next
 * step), all in C:
 *
 * - a periodic clock ticks at its shift and every interval after it: the interval given, else
 *   the FMU's (fmi3GetIntervalDecimal after initialization, and after each tick for a tunable
 *   or changing clock, whose interval the FMU may change);
 * - a triggered clock ticks at the times given;
 * - a countdown clock ticks when the FMU announced it in a partition (its clockUpdate callback,
 *   where the binding reads the interval), that interval after the announcing tick.
 *
 * Ticks at one instant run by priority (the lowest value first), then value reference, then the
 * order they were planned in: deterministic whatever the step. The inputs are written before
 * each partition; after it the outputs it moves are read, and each output clock that ticked is
 * an own event of the component (SSX_OWN_OUTPUT_CLOCK), as for a Co-Simulation FMU. Every tick
 * is logged with the values it moved, for the caller to read once after the run.
 *
 * The data starts with the FMU kinds' own, so their shared initialization, input writing and
 * preparation serve this kind too. */
#include <math.h>
#include <stdlib.h>

#include "array.h"
#include "component.h"
#include "component_setup.h"
#include "error.h"
#include "fmu_component.h"
#include "own_events.h"
#include "system.h"

/* An output a clock's tick moves. */
typedef struct {
    unsigned int vr;
    int port;
    ssx_value_type type;
} moved_output;

typedef struct {
    unsigned int vr;
    ssx_scheduled_clock_kind kind;
    long long priority;
    double interval; /* periodic: NaN until known (given, or the FMU's) */
    double shift;
    int interval_tunable; /* periodic: asked again after each tick */
    double *times;        /* triggered: the times given */
    size_t n_times;
    int countdown;        /* countdown: its index among the FMU's countdown clocks */
    int output;           /* output: its index among the FMU's output clocks */
    moved_output *moved;
    size_t n_moved;
    size_t moved_capacity;
} scheduled_clock;

typedef struct {
    double time;
    long long priority;
    unsigned int vr;
    long sequence;
    int clock;
} planned_tick;

/* One tick of the log: the values it moved are values[first .. the next tick's first). */
typedef struct {
    double time;
    int clock;
    size_t first;
} logged_tick;

typedef struct {
    int port;
    double value;
} logged_value;

typedef struct {
    fmu_component_data fmu; /* first: the FMU kinds' functions take the component */
    scheduled_clock *clocks;
    size_t n_clocks;
    size_t clock_capacity;
    int n_countdown;
    int n_output_clocks;
    planned_tick *plan;
    size_t n_planned;
    size_t plan_capacity;
    long sequence;
    logged_tick *ticks;
    size_t n_ticks;
    size_t tick_capacity;
    logged_value *values;
    size_t n_values;
    size_t value_capacity;
    /* where the binding hands out each partition's updates (ssx_fmu_take_clock_updates) */
    int *ticked;
    double *announced;
} scheduled_data;

/* a clock without a priority runs after every clock with one */
static const long long NO_PRIORITY = (long long)1 << 31;

static scheduled_data *data_of(const ssx_component *c)
{
    return (scheduled_data *)c->data;
}

static int out_of_memory(ssx_system *sys, const ssx_component *c, double t)
{
    return fail(sys, c->index, -1, t, "component '%s': out of memory planning its ticks",
                c->name);
}

static int fmi_failed(ssx_system *sys, const ssx_component *c, double t, int status,
                      const char *call)
{
    return fail_fmi(sys, c, data_of(c)->fmu.fmu, t, status, call);
}

/* ------------------------------------------------------------------ the plan of ticks */

static int before(const planned_tick *a, const planned_tick *b)
{
    if (a->time != b->time) {
        return a->time < b->time;
    }
    if (a->priority != b->priority) {
        return a->priority < b->priority;
    }
    if (a->vr != b->vr) {
        return a->vr < b->vr;
    }
    return a->sequence < b->sequence;
}

static int plan_tick(ssx_system *sys, ssx_component *c, int clock, double time)
{
    scheduled_data *d = data_of(c);
    if (array_reserve((void **)&d->plan, &d->plan_capacity, d->n_planned + 1, sizeof *d->plan,
                      8) != 0) {
        return out_of_memory(sys, c, time);
    }
    const scheduled_clock *k = &d->clocks[clock];
    d->plan[d->n_planned++] = (planned_tick){.time = time, .priority = k->priority,
                                             .vr = k->vr, .sequence = d->sequence++,
                                             .clock = clock};
    return 0;
}

/* The index of the first tick of the plan, or -1 when it is empty. */
static long first_planned(const scheduled_data *d)
{
    long first = -1;
    for (size_t i = 0; i < d->n_planned; ++i) {
        if (first < 0 || before(&d->plan[i], &d->plan[first])) {
            first = (long)i;
        }
    }
    return first;
}

/* ------------------------------------------------------------------ the log */

static int log_tick(ssx_system *sys, ssx_component *c, int clock, double time)
{
    scheduled_data *d = data_of(c);
    const scheduled_clock *k = &d->clocks[clock];
    if (array_reserve((void **)&d->ticks, &d->tick_capacity, d->n_ticks + 1, sizeof *d->ticks,
                      64) != 0 ||
        array_reserve((void **)&d->values, &d->value_capacity, d->n_values + k->n_moved,
                      sizeof *d->values, 64) != 0) {
        return out_of_memory(sys, c, time);
    }
    d->ticks[d->n_ticks++] = (logged_tick){.time = time, .clock = clock, .first = d->n_values};
    for (size_t i = 0; i < k->n_moved; ++i) {
        int port = k->moved[i].port;
        d->values[d->n_values++] = (logged_value){.port = port, .value = c->outputs[port]};
    }
    return 0;
}

/* ------------------------------------------------------------------ one tick */

/* Reads the outputs the tick of `clock` moves into the component's outputs. */
static int read_moved(ssx_system *sys, ssx_component *c, const scheduled_clock *k, double t)
{
    ssx_fmu *fmu = data_of(c)->fmu.fmu;
    for (size_t i = 0; i < k->n_moved; ++i) {
        const moved_output *m = &k->moved[i];
        double real = 0.0;
        int discrete = 0;
        int status = m->type == SSX_REAL      ? ssx_fmu_get_real(fmu, &m->vr, 1, &real)
                     : m->type == SSX_INTEGER ? ssx_fmu_get_integer(fmu, &m->vr, 1, &discrete)
                                              : ssx_fmu_get_boolean(fmu, &m->vr, 1, &discrete);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, t, status, ssx_fmu_last_call(fmu));
        }
        c->outputs[m->port] = m->type == SSX_REAL      ? real
                              : m->type == SSX_BOOLEAN ? (double)(discrete != 0)
                                                       : (double)discrete;
    }
    return 0;
}

/* The interval to a periodic clock's next tick: the known one for a clock whose interval is
 * fixed, else the FMU's latest changed one. */
static int next_interval(ssx_system *sys, ssx_component *c, scheduled_clock *k, double t)
{
    scheduled_data *d = data_of(c);
    if (!k->interval_tunable && !isnan(k->interval)) {
        return 0;
    }
    double interval = NAN;
    int qualifier = 0;
    int status = ssx_fmu_get_interval(d->fmu.fmu, k->vr, &interval, &qualifier);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, "fmi3GetIntervalDecimal");
    }
    if (qualifier == SSX_INTERVAL_CHANGED) {
        if (!(isfinite(interval) && interval > 0)) {
            return fail(sys, c->index, -1, t,
                        "component '%s': fmi3GetIntervalDecimal gives periodic clock %u the "
                        "interval %g; an interval is a positive number of seconds",
                        c->name, k->vr, interval);
        }
        k->interval = interval;
    }
    if (isnan(k->interval)) {
        return fail(sys, c->index, -1, t,
                    "component '%s': periodic clock %u has no interval (none was given, nor "
                    "does fmi3GetIntervalDecimal give one)", c->name, k->vr);
    }
    return 0;
}

static int activate(ssx_system *sys, ssx_component *c, int clock, double time)
{
    scheduled_data *d = data_of(c);
    scheduled_clock *k = &d->clocks[clock];
    /* every input before every partition, changed or not: a partition may consume its inputs
     * (the FMU's own values of them are not the engine's to trust) */
    d->fmu.inputs_written_epoch = -1;
    if (ssx_fmu_component_ops.write_inputs(sys, c) != 0) {
        return -1;
    }
    int status = ssx_fmu_activate_model_partition(d->fmu.fmu, k->vr, time);
    if (!fmi_ok(status)) {
        /* what the FMU or the binding said first: an unbalanced lock is no call's failure */
        const char *log = ssx_fmu_last_message(d->fmu.fmu);
        return fail_status(sys, c, time, status,
                           "%s: %s%sfmi3ActivateModelPartition returned %s at t=%.17g", c->name,
                           log, log[0] ? ": " : "", ssx_fmu_status_text(d->fmu.fmu, status),
                           time);
    }
    ssx_fmu_take_clock_updates(d->fmu.fmu, d->ticked, d->announced);
    if (read_moved(sys, c, k, time) != 0 || log_tick(sys, c, clock, time) != 0) {
        return -1;
    }
    /* the output clocks the partition ticked come after it, in the FMU's order */
    for (size_t i = 0; i < d->n_clocks; ++i) {
        const scheduled_clock *o = &d->clocks[i];
        if (o->kind == SSX_SCHEDULED_OUTPUT && d->ticked[o->output]) {
            if (log_tick(sys, c, (int)i, time) != 0 ||
                own_event_report_clock(sys, c, SSX_OWN_OUTPUT_CLOCK, o->output + 1, time) != 0) {
                return -1;
            }
        }
    }
    for (size_t i = 0; i < d->n_clocks; ++i) {
        const scheduled_clock *a = &d->clocks[i];
        if (a->kind == SSX_SCHEDULED_COUNTDOWN && isfinite(d->announced[a->countdown]) &&
            plan_tick(sys, c, (int)i, d->announced[a->countdown]) != 0) {
            return -1;
        }
    }
    if (k->kind == SSX_SCHEDULED_PERIODIC) {
        if (next_interval(sys, c, k, time) != 0 || plan_tick(sys, c, clock, time + k->interval)) {
            return -1;
        }
    }
    return 0;
}

static int scheduled_do_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    scheduled_data *d = data_of(c);
    double end = t + dt;
    double rounding = 1e-9 * fmax(1.0, fabs(end)); /* a tick at end - rounding is the next step's */
    for (long first = first_planned(d); first >= 0 && d->plan[first].time < end - rounding;
         first = first_planned(d)) {
        planned_tick tick = d->plan[first];
        d->plan[first] = d->plan[--d->n_planned];
        if (activate(sys, c, tick.clock, tick.time) != 0) {
            return -1;
        }
    }
    return 0;
}

/* ------------------------------------------------------------------ life cycle */

/* Out of initialization: every output read, the log emptied and the first ticks planned. */
static int start_schedule(ssx_system *sys, ssx_component *c, double t0)
{
    scheduled_data *d = data_of(c);
    d->n_planned = 0;
    d->sequence = 0;
    d->n_ticks = 0;
    d->n_values = 0;
    if (fmu_component_read_outputs_at(sys, c, t0) != 0) {
        return -1;
    }
    for (size_t i = 0; i < d->n_clocks; ++i) {
        scheduled_clock *k = &d->clocks[i];
        if (k->kind == SSX_SCHEDULED_PERIODIC) {
            if ((isnan(k->interval) && next_interval(sys, c, k, t0) != 0) ||
                plan_tick(sys, c, (int)i, t0 + k->shift) != 0) {
                return -1;
            }
        } else if (k->kind == SSX_SCHEDULED_TRIGGERED) {
            for (size_t j = 0; j < k->n_times; ++j) {
                if (k->times[j] >= t0 && plan_tick(sys, c, (int)i, k->times[j]) != 0) {
                    return -1;
                }
            }
        }
    }
    return 0;
}

static int scheduled_leave_initialization(ssx_system *sys, ssx_component *c, double t0)
{
    if (!ssx_fmu_in_initialization_mode(data_of(c)->fmu.fmu)) {
        return 0;
    }
    if (fmu_component_leave_initialization(sys, c, t0) != 0) {
        return -1;
    }
    return start_schedule(sys, c, t0);
}

/* The ports are read at each tick and written before each partition: between steps there is
 * nothing to move. */
static int scheduled_ports_in_place(ssx_system *sys, ssx_component *c)
{
    (void)sys;
    (void)c;
    return 0;
}

static int scheduled_evaluate_outputs(ssx_system *sys, ssx_component *c, double t)
{
    (void)sys;
    (void)c;
    (void)t;
    return 0;
}

static int no_snapshot(ssx_system *sys, ssx_component *c, int slot)
{
    (void)slot;
    return fail(sys, c->index, -1, sys->time,
                "component '%s': a Scheduled Execution FMU cannot be rolled back", c->name);
}

static int no_restore(ssx_system *sys, ssx_component *c, int slot, double t)
{
    (void)slot;
    return fail(sys, c->index, -1, t,
                "component '%s': a Scheduled Execution FMU cannot be rolled back", c->name);
}

static int never_rolls_back(const ssx_component *c)
{
    (void)c;
    return 0;
}

static void scheduled_release(ssx_component *c)
{
    scheduled_data *d = data_of(c);
    for (size_t i = 0; i < d->n_clocks; ++i) {
        free(d->clocks[i].times);
        free(d->clocks[i].moved);
    }
    free(d->clocks);
    free(d->plan);
    free(d->ticks);
    free(d->values);
    free(d->ticked);
    free(d->announced);
    fmu_component_data_free(&d->fmu);
}

static const ssx_component_ops scheduled_component_ops = {
    .do_step = scheduled_do_step,
    .write_inputs = scheduled_ports_in_place,
    .read_outputs = scheduled_ports_in_place,
    .evaluate_outputs = scheduled_evaluate_outputs,
    .snapshot = no_snapshot,
    .restore = no_restore,
    .release = scheduled_release,
    .adopt_inputs = fmu_component_adopt_inputs,
    .initial_outputs = fmu_component_initial_outputs,
    .leave_initialization = scheduled_leave_initialization,
    .shared_with_threads = fmu_component_instance,
    .prepare = fmu_component_prepare,
    .unprepare = fmu_component_unprepare,
    .can_roll_back = never_rolls_back,
    .fmu = fmu_component_fmu,
};

/* ------------------------------------------------------------------ the public calls */

/* c when it is a Scheduled Execution component, else NULL with the error set. */
static ssx_component *scheduled_component(ssx_system *sys, int component)
{
    ssx_component *c = system_component(sys, component);
    if (c != NULL && c->ops != &scheduled_component_ops) {
        fail_config(sys, component, -1, NAN,
                    "component '%s' is not a Scheduled Execution component", c->name);
        return NULL;
    }
    return c;
}

int ssx_add_scheduled_component(ssx_system *sys, const char *name, ssx_fmu *fmu)
{
    if (fmu == NULL) {
        return fail_config(sys, -1, -1, NAN, "component '%s': no FMU given", name ? name : "?");
    }
    size_t n_output = 0, n_triggered = 0;
    ssx_fmu_clock_counts(fmu, &n_output, &n_triggered);
    size_t n_countdown = ssx_fmu_countdown_clock_count(fmu);
    int *ticked = calloc(n_output ? n_output : 1, sizeof *ticked);
    double *announced = calloc(n_countdown ? n_countdown : 1, sizeof *announced);
    if (ticked == NULL || announced == NULL) {
        free(ticked);
        free(announced);
        return fail_config(sys, -1, -1, NAN, "out of memory adding component '%s'",
                           name ? name : "?");
    }
    int index = system_add_component(sys, name, 0, &scheduled_component_ops,
                                     sizeof(scheduled_data));
    if (index < 0) {
        free(ticked);
        free(announced);
        return -1;
    }
    scheduled_data *d = sys->components[index]->data;
    fmu_component_data_init(&d->fmu, fmu);
    d->ticked = ticked;
    d->announced = announced;
    return index;
}

int ssx_add_scheduled_clock(ssx_system *sys, int component, ssx_scheduled_clock_kind kind,
                            unsigned int vr, long long priority, double interval, double shift,
                            int interval_tunable)
{
    ssx_component *c = scheduled_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    scheduled_data *d = data_of(c);
    size_t n_output = 0, n_triggered = 0;
    ssx_fmu_clock_counts(d->fmu.fmu, &n_output, &n_triggered);
    size_t n_countdown = ssx_fmu_countdown_clock_count(d->fmu.fmu);
    if (kind < SSX_SCHEDULED_PERIODIC || kind > SSX_SCHEDULED_OUTPUT) {
        return fail_config(sys, component, -1, NAN, "component '%s': clock %u has kind %d, "
                           "not an ssx_scheduled_clock_kind", c->name, vr, (int)kind);
    }
    if (kind == SSX_SCHEDULED_PERIODIC &&
        (!(isnan(interval) || (isfinite(interval) && interval > 0)) || !isfinite(shift))) {
        return fail_config(sys, component, -1, NAN, "component '%s': periodic clock %u takes a "
                           "positive interval (NaN: the FMU's) and a finite shift, not %g and %g",
                           c->name, vr, interval, shift);
    }
    if ((kind == SSX_SCHEDULED_COUNTDOWN && (size_t)d->n_countdown >= n_countdown) ||
        (kind == SSX_SCHEDULED_OUTPUT && (size_t)d->n_output_clocks >= n_output)) {
        return fail_config(sys, component, -1, NAN, "component '%s': clock %u is one %s clock "
                           "more than its FMU was loaded with", c->name, vr,
                           kind == SSX_SCHEDULED_OUTPUT ? "output" : "countdown");
    }
    if (array_reserve((void **)&d->clocks, &d->clock_capacity, d->n_clocks + 1,
                      sizeof *d->clocks, 4) != 0) {
        return fail_config(sys, component, -1, NAN, "out of memory adding a clock");
    }
    d->clocks[d->n_clocks] = (scheduled_clock){
        .vr = vr, .kind = kind, .priority = priority < 0 ? NO_PRIORITY : priority,
        .interval = kind == SSX_SCHEDULED_PERIODIC ? interval : NAN,
        .shift = kind == SSX_SCHEDULED_PERIODIC ? shift : 0.0,
        .interval_tunable = kind == SSX_SCHEDULED_PERIODIC && interval_tunable,
        .countdown = kind == SSX_SCHEDULED_COUNTDOWN ? d->n_countdown++ : -1,
        .output = kind == SSX_SCHEDULED_OUTPUT ? d->n_output_clocks++ : -1};
    return (int)d->n_clocks++;
}

/* Clock `clock` of c, or NULL with the error set. */
static scheduled_clock *clock_of(ssx_system *sys, ssx_component *c, int clock)
{
    scheduled_data *d = data_of(c);
    if (clock < 0 || (size_t)clock >= d->n_clocks) {
        fail_config(sys, c->index, -1, NAN, "component '%s' has no clock %d (it has %zu)",
                    c->name, clock, d->n_clocks);
        return NULL;
    }
    return &d->clocks[clock];
}

int ssx_set_scheduled_clock_times(ssx_system *sys, int component, int clock, const double *times,
                                  size_t n)
{
    ssx_component *c = scheduled_component(sys, component);
    scheduled_clock *k = c != NULL ? clock_of(sys, c, clock) : NULL;
    if (k == NULL) {
        return -1;
    }
    if (k->kind != SSX_SCHEDULED_TRIGGERED) {
        return fail_config(sys, component, -1, NAN, "component '%s': clock %u is not "
                           "triggered; only a triggered clock ticks at given times", c->name,
                           k->vr);
    }
    double *copy = malloc((n ? n : 1) * sizeof *copy);
    if (copy == NULL) {
        return fail_config(sys, component, -1, NAN, "out of memory keeping clock times");
    }
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(times[i]) || (i > 0 && times[i] < times[i - 1])) {
            free(copy);
            return fail_config(sys, component, -1, NAN, "component '%s': the times of clock "
                               "%u are finite and do not decrease (time %zu is %g)", c->name,
                               k->vr, i, times[i]);
        }
        copy[i] = times[i];
    }
    free(k->times);
    k->times = copy;
    k->n_times = n;
    return 0;
}

int ssx_add_scheduled_clock_output(ssx_system *sys, int component, int clock, int output)
{
    ssx_component *c = scheduled_component(sys, component);
    scheduled_clock *k = c != NULL ? clock_of(sys, c, clock) : NULL;
    if (k == NULL) {
        return -1;
    }
    if (output < 0 || output >= c->n_outputs || k->kind == SSX_SCHEDULED_OUTPUT) {
        return fail_config(sys, component, -1, NAN, "component '%s': output %d is not one of "
                           "its %d outputs, or clock %u is an output clock (which moves none)",
                           c->name, output, c->n_outputs, k->vr);
    }
    ssx_value_type type = c->output_ports[output].type;
    if (type != SSX_REAL && type != SSX_INTEGER && type != SSX_BOOLEAN) {
        return fail_config(sys, component, -1, NAN, "component '%s': output %d is neither "
                           "Real, Integer nor Boolean", c->name, output);
    }
    if (array_reserve((void **)&k->moved, &k->moved_capacity, k->n_moved + 1,
                      sizeof *k->moved, 4) != 0) {
        return fail_config(sys, component, -1, NAN, "out of memory adding a clock's output");
    }
    k->moved[k->n_moved++] = (moved_output){.vr = c->output_ports[output].vr, .port = output,
                                            .type = type};
    return 0;
}

size_t ssx_scheduled_tick_count(ssx_system *sys, int component, size_t *n_values)
{
    ssx_component *c = scheduled_component(sys, component);
    scheduled_data *d = c != NULL ? data_of(c) : NULL;
    if (n_values != NULL) {
        *n_values = d != NULL ? d->n_values : 0;
    }
    return d != NULL ? d->n_ticks : 0;
}

int ssx_scheduled_ticks(ssx_system *sys, int component, double *time, int *clock,
                        size_t *first_value, int *output, double *value)
{
    ssx_component *c = scheduled_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    const scheduled_data *d = data_of(c);
    for (size_t k = 0; k < d->n_ticks; ++k) {
        time[k] = d->ticks[k].time;
        clock[k] = d->ticks[k].clock;
        first_value[k] = d->ticks[k].first;
    }
    first_value[d->n_ticks] = d->n_values;
    for (size_t i = 0; i < d->n_values; ++i) {
        output[i] = d->values[i].port;
        value[i] = d->values[i].value;
    }
    return 0;
}
