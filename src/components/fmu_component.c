/* Built-in behaviour of an FMU component: its FMI calls, batched by value type, what the
 * statuses of a step mean, and the events an FMI 3.0 FMU handles in its own step. */
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_component.h"
#include "byte_stream.h"
#include "component_setup.h"
#include "error.h"
#include "finite_outputs.h"
#include "fmu_backend.h"
#include "fmu_binding.h"
#include "own_events.h"
#include "system.h"

_Static_assert(offsetof(fmu_component_data, int_scratch) + sizeof(int *) <= 128,
               "what every step reads must stay in the data's first two cache lines");

/* The status every standard gives a step it could not complete (fmi2Discard, fmi3Discard). */
enum { STATUS_DISCARD = 2, STATUS_ERROR = 3 };

/* The standard's name of the call in `slot` of c's FMU, for messages. */
static const char *call_name(const ssx_component *c, ssx_fmu_slot slot)
{
    fmu_component_data *d = fmu_data(c);
    return ssx_fmu_function_name(d->fmu, (int)slot);
}

/* The call in `slot` of c's FMU returned `status` at t. */
static int fmi_failed(ssx_system *sys, const ssx_component *c, double t, int status,
                      ssx_fmu_slot slot)
{
    return fail_fmi(sys, c, fmu_data(c)->fmu, t, status, call_name(c, slot));
}

static int out_of_text_memory(ssx_system *sys, const ssx_component *c, double t)
{
    return fail(sys, c->index, -1, t, "out of memory keeping a String value of component '%s'",
                c->name);
}

/* The String outputs: each text's number in the system's table. */
static int read_texts(ssx_system *sys, ssx_component *c, double t)
{
    fmu_component_data *d = fmu_data(c);
    const fmu_port_batch *b = &d->text_outputs;
    int status = ssx_fmu_get_string(d->fmu, b->vr, b->n, d->text_scratch);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, SLOT_GET_STRING);
    }
    for (size_t i = 0; i < b->n; ++i) {
        if (text_table_number(&sys->texts, d->text_scratch[i], &c->outputs[b->port[i]]) != 0) {
            return out_of_text_memory(sys, c, t);
        }
    }
    return 0;
}

/* The Binary outputs: each value's number in the system's table. */
static int read_binaries(ssx_system *sys, ssx_component *c, double t)
{
    fmu_component_data *d = fmu_data(c);
    const fmu_port_batch *b = &d->binary_outputs;
    int status = ssx_fmu_get_binary(d->fmu, b->vr, b->n, d->size_scratch, d->binary_scratch);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, SLOT_GET_BINARY);
    }
    for (size_t i = 0; i < b->n; ++i) {
        if (text_table_bytes_number(&sys->texts, d->binary_scratch[i], d->size_scratch[i],
                                    &c->outputs[b->port[i]]) != 0) {
            return out_of_text_memory(sys, c, t);
        }
    }
    return 0;
}

/* The bytes of Binary input k and their size, or NULL after failing. */
static const unsigned char *input_bytes(ssx_system *sys, const ssx_component *c, int k,
                                        size_t *size, double t)
{
    const unsigned char *bytes = text_table_bytes(&sys->texts, c->inputs[k], size);
    if (bytes == NULL) {
        fail(sys, c->index, -1, t,
             "component '%s': Binary input %d holds %.17g, which numbers no value", c->name, k,
             c->inputs[k]);
    }
    return bytes;
}

/* The text of String input k, or NULL after failing: its value is no text's number. */
static const char *input_text(ssx_system *sys, const ssx_component *c, int k, double t)
{
    const char *text = text_table_text(&sys->texts, c->inputs[k]);
    if (text == NULL) {
        fail(sys, c->index, -1, t,
             "component '%s': String input %d holds %.17g, which numbers no text", c->name, k,
             c->inputs[k]);
    }
    return text;
}

int fmu_component_read_outputs_at(ssx_system *sys, ssx_component *c, double t)
{
    fmu_component_data *d = fmu_data(c);
    /* x - x is 0 for a finite x and NaN for NaN and infinities: one subtraction per value
     * instead of a classification (Integer and Boolean values are always finite) */
    double residue = 0.0;
    const fmu_port_batch *real = &d->real_outputs;
    if (real->n > 0) {
        int status = ssx_fmu_get_real(d->fmu, real->vr, real->n, d->real_scratch);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, t, status, SLOT_GET_REAL);
        }
        for (size_t i = 0; i < real->n; ++i) {
            double value = d->real_scratch[i];
            c->outputs[real->port[i]] = value;
            residue += value - value;
        }
    }
    for (int type = SSX_INTEGER; type <= SSX_BOOLEAN && d->has_discrete_ports; ++type) {
        const fmu_port_batch *b = &d->discrete_outputs[type - SSX_INTEGER];
        if (b->n == 0) {
            continue;
        }
        int status = type == SSX_INTEGER
                         ? ssx_fmu_get_integer(d->fmu, b->vr, b->n, d->int_scratch)
                         : ssx_fmu_get_boolean(d->fmu, b->vr, b->n, d->int_scratch);
        if (!fmi_ok(status)) {
            ssx_fmu_slot slot = type == SSX_INTEGER ? SLOT_GET_INTEGER : SLOT_GET_BOOLEAN;
            return fmi_failed(sys, c, t, status, slot);
        }
        for (size_t i = 0; i < b->n; ++i) {
            int value = d->int_scratch[i];
            c->outputs[b->port[i]] = type == SSX_BOOLEAN ? (value != 0) : (double)value;
        }
    }
    if (d->text_outputs.n > 0 && read_texts(sys, c, t) != 0) {
        return -1;
    }
    if (d->binary_outputs.n > 0 && read_binaries(sys, c, t) != 0) {
        return -1;
    }
    return residue == 0.0 ? 0 : component_check_outputs(sys, c, t);
}

static int fmu_read_outputs(ssx_system *sys, ssx_component *c)
{
    return fmu_component_read_outputs_at(sys, c, sys->time);
}

/* Whether the FMU already holds every input value: nothing set it since the engine's last write
 * (connected inputs change each step; unconnected ones only when Python writes them). */
int fmu_component_inputs_unchanged(const ssx_component *c)
{
    fmu_component_data *d = fmu_data(c);
    if (d->inputs_written_epoch != ssx_fmu_values_epoch(d->fmu)) {
        return 0;
    }
    for (int i = 0; i < c->n_inputs; ++i) {
        if (c->inputs[i] != d->inputs_written[i]) {
            return 0;
        }
    }
    return 1;
}

/* An Integer input's value is an int at the FMU boundary; one beyond it cannot be written. */
static int integer_out_of_range(ssx_system *sys, ssx_component *c, unsigned int vr, double value)
{
    fmu_component_data *d = fmu_data(c);
    const char *name = ssx_fmu_variable_name(d->fmu, vr);
    return fail(sys, c->index, -1, sys->time,
                "component '%s': input %s%s%s(value reference %u) receives %.17g at t=%.17g, "
                "outside the range of the engine's Integer ports (%d..%d)",
                c->name, name[0] ? "'" : "", name, name[0] ? "' " : "", vr, value, sys->time,
                INT_MIN, INT_MAX);
}

static int write_values(ssx_system *sys, ssx_component *c);

static int fmu_write_inputs(ssx_system *sys, ssx_component *c)
{
    if (!fmu_component_inputs_unchanged(c) && write_values(sys, c) != 0) {
        return -1;
    }
    return sys->write_input_derivatives != NULL ? sys->write_input_derivatives(sys, c) : 0;
}

static int write_values(ssx_system *sys, ssx_component *c)
{
    fmu_component_data *d = fmu_data(c);
    const fmu_port_batch *real = &d->real_inputs;
    if (real->n > 0) {
        for (size_t i = 0; i < real->n; ++i) {
            d->real_scratch[i] = c->inputs[real->port[i]];
        }
        int status = ssx_fmu_set_real(d->fmu, real->vr, real->n, d->real_scratch);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, sys->time, status, SLOT_SET_REAL);
        }
    }
    for (int type = SSX_INTEGER; type <= SSX_BOOLEAN && d->has_discrete_ports; ++type) {
        const fmu_port_batch *b = &d->discrete_inputs[type - SSX_INTEGER];
        if (b->n == 0) {
            continue;
        }
        for (size_t i = 0; i < b->n; ++i) {
            double value = c->inputs[b->port[i]];
            if (type == SSX_INTEGER && !(value > INT_MIN - 0.5 && value < INT_MAX + 0.5)) {
                return integer_out_of_range(sys, c, b->vr[i], value);
            }
            /* integers round to nearest: a scaled connection may land a hair off an integer */
            d->int_scratch[i] = type == SSX_BOOLEAN ? (value != 0.0)
                                                    : (int)(value < 0 ? value - 0.5 : value + 0.5);
        }
        int status = type == SSX_INTEGER
                         ? ssx_fmu_set_integer(d->fmu, b->vr, b->n, d->int_scratch)
                         : ssx_fmu_set_boolean(d->fmu, b->vr, b->n, d->int_scratch);
        if (!fmi_ok(status)) {
            ssx_fmu_slot slot = type == SSX_INTEGER ? SLOT_SET_INTEGER : SLOT_SET_BOOLEAN;
            return fmi_failed(sys, c, sys->time, status, slot);
        }
    }
    const fmu_port_batch *texts = &d->text_inputs;
    if (texts->n > 0) {
        for (size_t i = 0; i < texts->n; ++i) {
            d->text_scratch[i] = input_text(sys, c, texts->port[i], sys->time);
            if (d->text_scratch[i] == NULL) {
                return -1;
            }
        }
        int status = ssx_fmu_set_string(d->fmu, texts->vr, texts->n, d->text_scratch);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, sys->time, status, SLOT_SET_STRING);
        }
    }
    const fmu_port_batch *binaries = &d->binary_inputs;
    if (binaries->n > 0) {
        for (size_t i = 0; i < binaries->n; ++i) {
            d->binary_scratch[i] = input_bytes(sys, c, binaries->port[i], &d->size_scratch[i],
                                               sys->time);
            if (d->binary_scratch[i] == NULL) {
                return -1;
            }
        }
        int status = ssx_fmu_set_binary(d->fmu, binaries->vr, binaries->n, d->size_scratch,
                                        d->binary_scratch);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, sys->time, status, SLOT_SET_BINARY);
        }
    }
    if (c->n_inputs > 0) {
        memcpy(d->inputs_written, c->inputs, (size_t)c->n_inputs * sizeof(double));
    }
    d->inputs_written_epoch = ssx_fmu_values_epoch(d->fmu);
    return 0;
}

/* The FMU asked to end the simulation at `reached` during the step from t to t_end: the request
 * is kept for the run to end cleanly, and the step counts as done when the FMU reached its end. */
static int stop_requested(ssx_system *sys, ssx_component *c, double t, double t_end,
                          double reached, const char *log)
{
    double stop = isnan(reached) ? t : reached;
    /* the first request of the run counts; on a worker thread, the first of its share */
    ssx_termination *request = termination_record(sys);
    if (request->component < 0) {
        request->component = c->index;
        request->time = stop;
        snprintf(request->message, sizeof request->message, "%s", log);
    }
    /* the grid's own rounding: a remainder below 1e-9 steps is the step's end */
    if (reached >= t_end - 1e-9 * (t_end - t)) {
        return fmu_component_read_outputs_at(sys, c, t_end);
    }
    return fail(sys, c->index, -1, t,
                "component '%s' asked to stop at t=%.17g, inside the step from %.17g to %.17g",
                c->name, stop, t, t_end);
}

/* A discarded step means one of two things. The FMU asks to end the simulation (FMI 2.0's
 * fmi2Terminated, FMI 3.0's terminateSimulation): see stop_requested. Otherwise the FMU could
 * not complete the step: a failure that says how far it got (its last successful time). */
static int discarded_step(ssx_system *sys, ssx_component *c, double t, double t_end)
{
    fmu_component_data *d = fmu_data(c);
    char log[sizeof sys->termination.message];
    snprintf(log, sizeof log, "%s", ssx_fmu_last_message(d->fmu)); /* before queries overwrite it */
    int terminated = 0;
    double reached = NAN;
    int asked = ssx_fmu_get_terminated(d->fmu, &terminated);
    if (!fmi_ok(ssx_fmu_get_last_successful_time(d->fmu, &reached))) {
        reached = NAN;
    }
    if (!fmi_ok(asked) || !terminated) {
        fmu_step_outcome outcome;
        ssx_fmu_step_outcome(d->fmu, &outcome);
        /* FMI 2.0 asks a status function; FMI 3.0's doStep says it itself */
        const char *reached_name = outcome.reported ? "lastSuccessfulTime"
                                                    : "fmi2LastSuccessfulTime";
        char got_to[96] = "fmi2GetRealStatus(fmi2LastSuccessfulTime) failed";
        if (!isnan(reached)) {
            snprintf(got_to, sizeof got_to, "%s=%.17g", reached_name, reached);
        }
        return fail_status(sys, c, isnan(reached) ? t : reached, STATUS_DISCARD,
                           "component '%s': %s from t=%.17g to %.17g returned %s without asking "
                           "to terminate: the FMU completed the step only up to %s%s%s%s",
                           c->name, call_name(c, SLOT_DO_STEP), t, t_end,
                           ssx_fmu_status_text(d->fmu, STATUS_DISCARD), got_to,
                           log[0] ? " (FMU log: " : "", log,
                           log[0] ? ")" : " (the FMU logged no message)");
    }
    return stop_requested(sys, c, t, t_end, reached, log);
}

/* One doStep from t to t_end and what its status means; the outcome of a completed call is
 * left in *outcome. 1: the call completed; 0: the step is over (the FMU asked to stop, or the
 * call failed: the return of `done` says which). */
static int step_call(ssx_system *sys, ssx_component *c, double t, double t_end,
                     fmu_step_outcome *outcome, int *done)
{
    fmu_component_data *d = fmu_data(c);
    /* In hybrid mode the engine may set an earlier state again, so it must not promise not to. */
    int status = ssx_fmu_do_step(d->fmu, t, t_end - t, !sys->stepping_hybrid);
    if (status == STATUS_DISCARD) {
        *done = discarded_step(sys, c, t, t_end);
        return 0;
    }
    if (!fmi_ok(status)) {
        *done = fmi_failed(sys, c, t, status, SLOT_DO_STEP);
        return 0;
    }
    ssx_fmu_step_outcome(d->fmu, outcome);
    return 1;
}

/* In Event Mode at t_e: which output clocks tick (NULL in *active without output clocks;
 * else an array the caller frees). */
static int read_output_clocks(ssx_system *sys, ssx_component *c, double t_e, int **active)
{
    fmu_component_data *d = fmu_data(c);
    size_t n_output = 0, n_triggered = 0;
    ssx_fmu_clock_counts(d->fmu, &n_output, &n_triggered);
    *active = NULL;
    if (n_output == 0) {
        return 0;
    }
    *active = calloc(n_output, sizeof **active);
    if (*active == NULL) {
        return fail(sys, c->index, -1, t_e,
                    "component '%s': out of memory reading its output clocks at t=%.17g",
                    c->name, t_e);
    }
    int status = ssx_fmu_read_output_clocks(d->fmu, *active);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, t_e, status, SLOT_GET_CLOCK);
}

/* The event's own record, then one per output clock that ticked (in their order). */
static int report_event(ssx_system *sys, ssx_component *c, double t_e, int tick, int triggered,
                        const int *output_active)
{
    ssx_own_event_kind kind = tick || triggered >= 0 ? SSX_OWN_CLOCK_TICK : SSX_OWN_FMU_EVENT;
    if (own_event_report_clock(sys, c, kind, triggered + 1, t_e) != 0) {
        return -1;
    }
    size_t n_output = 0, n_triggered = 0;
    ssx_fmu_clock_counts(fmu_data(c)->fmu, &n_output, &n_triggered);
    for (size_t k = 0; output_active != NULL && k < n_output; ++k) {
        if (output_active[k] &&
            own_event_report_clock(sys, c, SSX_OWN_OUTPUT_CLOCK, (int)k + 1, t_e) != 0) {
            return -1;
        }
    }
    return 0;
}

/* An event the FMU found at t_e, a tick of its periodic input clocks there (`tick`), or a tick
 * of its triggered input clock `triggered` (-1: none), handled in event mode: the clocks tick
 * with the inputs of the step, the output clocks are read, its discrete states are updated
 * until they settle (more rounds than max_microsteps is chattering), then it steps again.
 * *terminate is set when the FMU asks to end the simulation there. */
static int handle_own_event(ssx_system *sys, ssx_component *c, double t_e, int tick,
                            int triggered, int *terminate)
{
    fmu_component_data *d = fmu_data(c);
    int status = ssx_fmu_enter_event_mode(d->fmu);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t_e, status, SLOT_ENTER_EVENT_MODE);
    }
    status = tick ? ssx_fmu_tick_clocks(d->fmu, t_e)
                  : triggered >= 0 ? ssx_fmu_tick_triggered_clock(d->fmu, (size_t)triggered) : 0;
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t_e, status, SLOT_SET_CLOCK);
    }
    int *output_active = NULL;
    int result = read_output_clocks(sys, c, t_e, &output_active);
    ssx_fmu_event_info update = {.new_discrete_states_needed = 1};
    for (int round = 0; result == 0 && update.new_discrete_states_needed &&
                        !update.terminate_simulation;
         ++round) {
        if (round == sys->hybrid.max_microsteps) {
            result = fail_zeno(sys, c->index, -1, t_e,
                               "component '%s': %s still asked for another round after %d "
                               "rounds at t=%.17g (chattering; max_microsteps=%d)",
                               c->name, call_name(c, SLOT_NEW_DISCRETE_STATES), round, t_e,
                               sys->hybrid.max_microsteps);
            break;
        }
        status = ssx_fmu_new_discrete_states(d->fmu, &update);
        if (!fmi_ok(status)) {
            result = fmi_failed(sys, c, t_e, status, SLOT_NEW_DISCRETE_STATES);
        }
    }
    *terminate = update.terminate_simulation;
    if (result == 0 && !*terminate) {
        /* the countdown clocks announced in this Event Mode tick that long after it */
        status = ssx_fmu_plan_clocks(d->fmu, t_e);
        if (!fmi_ok(status)) {
            result = fmi_failed(sys, c, t_e, status, SLOT_GET_INTERVAL);
        }
    }
    if (result == 0 && !*terminate) {
        status = ssx_fmu_enter_step_mode(d->fmu);
        if (!fmi_ok(status)) {
            result = fmi_failed(sys, c, t_e, status, SLOT_ENTER_STEP_MODE);
        }
    }
    if (result == 0) {
        result = report_event(sys, c, t_e, tick, triggered, output_active);
    }
    free(output_active);
    return result;
}

/* The triggered input clock `clock` ticks at t, where the component stands: its inputs are
 * written, it goes through Event Mode, its outputs are read, and the tick (and any output
 * clock that ticks with it) is reported as its own event at t. */
static int fmu_tick_triggered_clock(ssx_system *sys, ssx_component *c, int clock, double t)
{
    /* the tick samples the inputs the engine holds for the component now */
    int terminate = 0;
    if (fmu_write_inputs(sys, c) != 0 || handle_own_event(sys, c, t, 0, clock, &terminate) != 0) {
        return -1;
    }
    if (terminate) {
        return stop_requested(sys, c, t, t, t, ssx_fmu_last_message(fmu_data(c)->fmu));
    }
    return fmu_component_read_outputs_at(sys, c, t);
}

/* The rest of an FMI 3.0 step that returned early, needs its events handled or asks to stop:
 * each event is handled at the time the FMU returned (or at the step's end) and reported as the
 * component's own, and the FMU steps on from there until the step's end. No rollback: the FMU
 * knows the time of its events. */
static int step_on(ssx_system *sys, ssx_component *c, double t, double t_end,
                   fmu_step_outcome outcome)
{
    fmu_component_data *d = fmu_data(c);
    double close = 1e-9 * (t_end - t); /* the grid's own rounding */
    double from = t;
    int stuck = 0; /* returns in a row that did not advance */
    for (;;) {
        double reached = outcome.early_return ? outcome.last_successful_time : t_end;
        if (!(reached >= from - close && reached <= t_end + close)) {
            /* an FMU that claims to have gone past the step (or before it, or NaN) would be
             * read at a time it never reached */
            return fail_status(sys, c, from, STATUS_ERROR,
                               "component '%s': %s from t=%.17g returned early at "
                               "lastSuccessfulTime=%.17g, outside the step's end t=%.17g",
                               c->name, call_name(c, SLOT_DO_STEP), from, reached, t_end);
        }
        int terminate = outcome.terminate_simulation;
        size_t pending_before = own_events_pending_count(c);
        if (!terminate && outcome.event_handling_needed &&
            handle_own_event(sys, c, reached, 0, -1, &terminate) != 0) {
            return -1;
        }
        if (outcome.events_at_step_end) {
            own_events_mark_at_step_end(c, pending_before);
        }
        if (!terminate && outcome.clock_tick &&
            handle_own_event(sys, c, reached, 1, -1, &terminate) != 0) {
            return -1;
        }
        if (terminate) {
            return stop_requested(sys, c, t, t_end, reached, ssx_fmu_last_message(d->fmu));
        }
        if (reached >= t_end - close) {
            return fmu_component_read_outputs_at(sys, c, t_end);
        }
        stuck = reached > from ? 0 : stuck + 1;
        if (stuck > sys->hybrid.max_microsteps) {
            return fail_zeno(sys, c->index, -1, reached,
                             "component '%s' returned early from %s %d times in a row at "
                             "t=%.17g without advancing (chattering; max_microsteps=%d)",
                             c->name, call_name(c, SLOT_DO_STEP), stuck, reached,
                             sys->hybrid.max_microsteps);
        }
        from = reached;
        int done = 0;
        if (!step_call(sys, c, from, t_end, &outcome, &done)) {
            return done;
        }
    }
}

static int fmu_do_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    fmu_step_outcome outcome;
    int done = 0;
    if (!step_call(sys, c, t, t + dt, &outcome, &done)) {
        return done;
    }
    if (outcome.early_return || outcome.event_handling_needed || outcome.terminate_simulation ||
        outcome.clock_tick) {
        return step_on(sys, c, t, t + dt, outcome);
    }
    return fmu_component_read_outputs_at(sys, c, t + dt);
}

static int fmu_evaluate_outputs(ssx_system *sys, ssx_component *c, double t)
{
    (void)t;
    /* Our FMUs compute outputs from the current inputs: setting then getting is a zero-time
     * evaluation. */
    if (fmu_write_inputs(sys, c) != 0) {
        return -1;
    }
    return fmu_read_outputs(sys, c);
}

static int fmu_snapshot(ssx_system *sys, ssx_component *c, int slot)
{
    fmu_component_data *d = fmu_data(c);
    long generation = ssx_fmu_generation(d->fmu);
    if (d->fmu_state_generation[slot] != generation) {
        d->fmu_state[slot] = NULL; /* released with its instance by the binding */
        d->fmu_state_generation[slot] = generation;
    }
    int status = ssx_fmu_get_state(d->fmu, &d->fmu_state[slot]);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, sys->time, status, SLOT_GET_STATE);
    }
    return 0;
}

static int fmu_restore(ssx_system *sys, ssx_component *c, int slot, double t)
{
    fmu_component_data *d = fmu_data(c);
    /* a restore is followed by stepping again, which a component that asked to stop refuses */
    if (sys->termination.component >= 0) {
        return fail(sys, c->index, -1, t,
                    "component '%s' asked to stop at t=%.17g: the system is not stepped again",
                    sys->components[sys->termination.component]->name, sys->termination.time);
    }
    if (d->fmu_state[slot] == NULL ||
        d->fmu_state_generation[slot] != ssx_fmu_generation(d->fmu)) {
        return fail(sys, c->index, -1, t,
                    "component '%s': no FMU state in snapshot slot %d for the live instance "
                    "(was the FMU instantiated again after the snapshot?)",
                    c->name, slot);
    }
    int status = ssx_fmu_set_state(d->fmu, d->fmu_state[slot]);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, SLOT_SET_STATE);
    }
    return 0;
}

/* An input the user never set keeps the FMU's own value: the declared start may be a rounded
 * print of it (exporters write 1e-7 as 0.000000), so writing the start could change the model.
 * Reading the value lets the engine treat the input like any other. */
int fmu_component_adopt_inputs(ssx_system *sys, ssx_component *c, double t0)
{
    fmu_component_data *d = fmu_data(c);
    for (int k = 0; k < c->n_inputs; ++k) {
        if (c->input_driver[k] >= 0 || !isnan(c->input_starts[k])) {
            continue;
        }
        unsigned int vr = c->input_ports[k].vr;
        ssx_value_type type = c->input_ports[k].type;
        if (type == SSX_STRING) {
            const char *text = NULL;
            int status = ssx_fmu_get_string(d->fmu, &vr, 1, &text);
            if (!fmi_ok(status)) {
                return fmi_failed(sys, c, t0, status, SLOT_GET_STRING);
            }
            if (text_table_number(&sys->texts, text, &c->inputs[k]) != 0) {
                return out_of_text_memory(sys, c, t0);
            }
            continue;
        }
        if (type == SSX_BINARY) {
            const unsigned char *bytes = NULL;
            size_t size = 0;
            int status = ssx_fmu_get_binary(d->fmu, &vr, 1, &size, &bytes);
            if (!fmi_ok(status)) {
                return fmi_failed(sys, c, t0, status, SLOT_GET_BINARY);
            }
            if (text_table_bytes_number(&sys->texts, bytes, size, &c->inputs[k]) != 0) {
                return out_of_text_memory(sys, c, t0);
            }
            continue;
        }
        double real = 0.0;
        int integer = 0;
        int status = type == SSX_REAL      ? ssx_fmu_get_real(d->fmu, &vr, 1, &real)
                     : type == SSX_INTEGER ? ssx_fmu_get_integer(d->fmu, &vr, 1, &integer)
                                           : ssx_fmu_get_boolean(d->fmu, &vr, 1, &integer);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, t0, status,
                              type == SSX_REAL      ? SLOT_GET_REAL
                              : type == SSX_INTEGER ? SLOT_GET_INTEGER
                                                    : SLOT_GET_BOOLEAN);
        }
        c->inputs[k] = type == SSX_REAL ? real : type == SSX_BOOLEAN ? (integer != 0) : integer;
    }
    return 0;
}

/* The driven inputs of one numeric batch, in one Set call as write_values makes (an FMI 3.0
 * array's elements together). */
static int write_driven_batch(ssx_system *sys, ssx_component *c, const fmu_port_batch *b,
                              ssx_value_type type, double t0)
{
    fmu_component_data *d = fmu_data(c);
    unsigned int *vr = malloc((b->n + 1) * sizeof *vr);
    double *reals = malloc((b->n + 1) * sizeof *reals);
    int *discrete = malloc((b->n + 1) * sizeof *discrete);
    int status = vr != NULL && reals != NULL && discrete != NULL
                     ? 0
                     : fail(sys, c->index, -1, t0, "out of memory initializing component '%s'",
                            c->name);
    size_t n = 0;
    for (size_t i = 0; i < b->n && status == 0; ++i) {
        double value = c->inputs[b->port[i]];
        if (c->input_driver[b->port[i]] < 0) {
            continue;
        }
        if (type == SSX_INTEGER && !(value > INT_MIN - 0.5 && value < INT_MAX + 0.5)) {
            status = integer_out_of_range(sys, c, b->vr[i], value);
            break;
        }
        vr[n] = b->vr[i];
        reals[n] = value;
        discrete[n++] = type == SSX_BOOLEAN ? (value != 0.0)
                                            : (int)(value < 0 ? value - 0.5 : value + 0.5);
    }
    if (status == 0 && n > 0) {
        int set = type == SSX_REAL      ? ssx_fmu_set_real(d->fmu, vr, n, reals)
                  : type == SSX_INTEGER ? ssx_fmu_set_integer(d->fmu, vr, n, discrete)
                                        : ssx_fmu_set_boolean(d->fmu, vr, n, discrete);
        status = fmi_ok(set) ? 0
                             : fmi_failed(sys, c, t0, set,
                                          type == SSX_REAL      ? SLOT_SET_REAL
                                          : type == SSX_INTEGER ? SLOT_SET_INTEGER
                                                                : SLOT_SET_BOOLEAN);
    }
    free(vr);
    free(reals);
    free(discrete);
    return status;
}

/* The driven inputs in initialization mode, texts and bytes one call each, numbers one call per
 * type: an input with no driver keeps what the FMU was given (its NaN start, the FMU's own
 * value, is not read until it leaves). */
static int write_driven_inputs(ssx_system *sys, ssx_component *c, double t0)
{
    fmu_component_data *d = fmu_data(c);
    for (int k = 0; k < c->n_inputs; ++k) {
        if (c->input_driver[k] < 0) {
            continue;
        }
        unsigned int vr = c->input_ports[k].vr;
        ssx_value_type type = c->input_ports[k].type;
        if (type == SSX_STRING) {
            const char *text = input_text(sys, c, k, t0);
            int status = text != NULL ? ssx_fmu_set_string(d->fmu, &vr, 1, &text) : 0;
            if (text == NULL || !fmi_ok(status)) {
                return text == NULL ? -1 : fmi_failed(sys, c, t0, status, SLOT_SET_STRING);
            }
            continue;
        }
        if (type == SSX_BINARY) {
            size_t size = 0;
            const unsigned char *bytes = input_bytes(sys, c, k, &size, t0);
            int status = bytes != NULL ? ssx_fmu_set_binary(d->fmu, &vr, 1, &size, &bytes) : 0;
            if (bytes == NULL || !fmi_ok(status)) {
                return bytes == NULL ? -1 : fmi_failed(sys, c, t0, status, SLOT_SET_BINARY);
            }
        }
    }
    if (write_driven_batch(sys, c, &d->real_inputs, SSX_REAL, t0) != 0) {
        return -1;
    }
    for (int type = SSX_INTEGER; type <= SSX_BOOLEAN && d->has_discrete_ports; ++type) {
        if (write_driven_batch(sys, c, &d->discrete_inputs[type - SSX_INTEGER], type, t0) != 0) {
            return -1;
        }
    }
    return 0;
}

int fmu_component_initial_outputs(ssx_system *sys, ssx_component *c, double t0)
{
    fmu_component_data *d = fmu_data(c);
    if (!ssx_fmu_in_initialization_mode(d->fmu)) {
        return 0;
    }
    if (write_driven_inputs(sys, c, t0) != 0) {
        return -1;
    }
    /* FMI 1.0 computes its outputs in its initializing call: there are none to read before */
    return ssx_fmu_reads_in_initialization_mode(d->fmu) ? fmu_component_read_outputs_at(sys, c, t0)
                                                         : 0;
}

int fmu_component_leave_initialization(ssx_system *sys, ssx_component *c, double t0)
{
    fmu_component_data *d = fmu_data(c);
    if (!ssx_fmu_in_initialization_mode(d->fmu)) {
        return 0;
    }
    if (write_driven_inputs(sys, c, t0) != 0) {
        return -1;
    }
    int status = ssx_fmu_exit_initialization_mode(d->fmu);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, t0, status, SLOT_EXIT_INITIALIZATION_MODE);
}

int fmu_component_directional_derivative(ssx_system *sys, ssx_component *c,
                                         const unsigned int *outputs, size_t n_outputs,
                                         const unsigned int *inputs, size_t n_inputs,
                                         const double *seed, double *out, double t)
{
    fmu_component_data *d = fmu_data(c);
    int status = ssx_fmu_get_directional_derivative(d->fmu, outputs, n_outputs, inputs,
                                                    n_inputs, seed, out);
    return fmi_ok(status) ? 0
                          : fail_fmi(sys, c, d->fmu, t, status, "fmi2GetDirectionalDerivative");
}

const void *fmu_component_instance(const ssx_component *c)
{
    return fmu_data(c)->fmu;
}

ssx_fmu *fmu_component_fmu(const ssx_component *c)
{
    return fmu_data(c)->fmu;
}

ssx_fmu *fmu_component_binding(const ssx_component *c)
{
    return c->ops->fmu != NULL ? c->ops->fmu(c) : NULL;
}

ssx_component_capabilities fmu_component_capabilities(const ssx_component *c)
{
    return fmu_data(c)->capabilities;
}

int fmu_component_can_roll_back(const ssx_component *c)
{
    if (c->hooks.snapshot != NULL || c->hooks.restore != NULL) {
        /* half a pair cannot roll back consistently */
        return c->hooks.snapshot != NULL && c->hooks.restore != NULL;
    }
    return c->can_snapshot;
}

int fmu_component_output_derivatives(ssx_system *sys, ssx_component *c, double t, double *slope)
{
    fmu_component_data *d = fmu_data(c);
    const fmu_port_batch *real = &d->real_outputs;
    for (size_t j = 0; j < real->n; ++j) {
        d->int_scratch[j] = 1;
    }
    int status = ssx_fmu_get_real_output_derivatives(d->fmu, real->vr, real->n, d->int_scratch,
                                                     d->real_scratch);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, SLOT_GET_OUTPUT_DERIVATIVES);
    }
    for (size_t j = 0; j < real->n; ++j) {
        slope[real->port[j]] = d->real_scratch[j];
    }
    return 0;
}

/* The write's value references and orders, for `order` derivatives of every Real input; -1:
 * out of memory. */
static int lay_out_derivatives(fmu_component_data *d, int order)
{
    const fmu_port_batch *real = &d->real_inputs;
    size_t n = real->n * (size_t)order;
    if (n > d->derivative_capacity) {
        unsigned int *vr = realloc(d->derivative_vr, n * sizeof *vr);
        if (vr != NULL) {
            d->derivative_vr = vr;
        }
        int *orders = realloc(d->derivative_order, n * sizeof *orders);
        if (orders != NULL) {
            d->derivative_order = orders;
        }
        double *values = realloc(d->derivative_values, n * sizeof *values);
        if (values != NULL) {
            d->derivative_values = values;
        }
        if (vr == NULL || orders == NULL || values == NULL) {
            return -1;
        }
        d->derivative_capacity = n;
    }
    for (int k = 1; k <= order; ++k) {
        for (size_t j = 0; j < real->n; ++j) {
            size_t at = (size_t)(k - 1) * real->n + j;
            d->derivative_vr[at] = real->vr[j];
            d->derivative_order[at] = k;
        }
    }
    return 0;
}

int fmu_component_set_input_derivatives(ssx_system *sys, ssx_component *c, int order,
                                        const double *derivatives)
{
    fmu_component_data *d = fmu_data(c);
    const fmu_port_batch *real = &d->real_inputs;
    size_t n = real->n * (size_t)order;
    if (n == 0) {
        return 0;
    }
    if (n > d->derivative_capacity || d->derivative_order[n - 1] != order) {
        if (lay_out_derivatives(d, order) != 0) {
            return fail(sys, c->index, -1, sys->time,
                        "component '%s': out of memory writing input derivatives", c->name);
        }
    }
    for (size_t at = 0; at < n; ++at) {
        int port = real->port[at % real->n];
        d->derivative_values[at] = derivatives[2 * port + d->derivative_order[at] - 1];
    }
    int status = ssx_fmu_set_real_input_derivatives(d->fmu, d->derivative_vr, n,
                                                    d->derivative_order, d->derivative_values);
    if (status == 2 || status == 3) { /* Discard or Error, not Fatal */
        return 1; /* this order refused: the caller offers a lower one */
    }
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, sys->time, status, SLOT_SET_INPUT_DERIVATIVES);
    }
    return 0;
}

/* The ports of one type, each with its value reference, in the arrays at vr and port. */
static void build_batch(fmu_port_batch *b, const ssx_port *ports, int n_ports,
                        ssx_value_type type, unsigned int *vr, int *port)
{
    *b = (fmu_port_batch){.vr = vr, .port = port, .n = 0};
    for (int i = 0; i < n_ports; ++i) {
        if (ports[i].type == type) {
            b->vr[b->n] = ports[i].vr;
            b->port[b->n] = i;
            b->n++;
        }
    }
}

/* The step block lies in the system's prepared blocks, which go back after this; the
 * derivatives' arrays grow as used and are the component's own. */
static void free_prepared(fmu_component_data *d)
{
    free(d->derivative_vr);
    free(d->derivative_order);
    free(d->derivative_values);
    d->step_block = NULL;
    d->real_outputs = d->real_inputs = (fmu_port_batch){0};
    memset(d->discrete_outputs, 0, sizeof d->discrete_outputs);
    memset(d->discrete_inputs, 0, sizeof d->discrete_inputs);
    d->has_discrete_ports = 0;
    d->real_scratch = NULL;
    d->int_scratch = NULL;
    d->inputs_written = NULL;
    d->derivative_vr = NULL;
    d->derivative_order = NULL;
    d->derivative_values = NULL;
    d->derivative_capacity = 0;
    free(d->text_scratch);
    d->text_scratch = NULL;
    d->text_outputs = d->text_inputs = (fmu_port_batch){0};
    free(d->binary_scratch);
    free(d->size_scratch);
    d->binary_scratch = NULL;
    d->size_scratch = NULL;
    d->binary_outputs = d->binary_inputs = (fmu_port_batch){0};
}

void fmu_component_unprepare(ssx_component *c)
{
    free_prepared(fmu_data(c));
}

/* What a step reads besides the ports (batches, scratch, the inputs last written) in one
 * block, right after the member's links (component_prepare): doubles first, then value
 * references, port indices and the Integer scratch. */
int fmu_component_prepare(ssx_system *sys, ssx_component *c)
{
    fmu_component_data *d = fmu_data(c);
    free_prepared(d);
    size_t widest = (size_t)(c->n_outputs > c->n_inputs ? c->n_outputs : c->n_inputs) + 1;
    size_t n_written = (size_t)c->n_inputs + 1;
    size_t n_ports = (size_t)c->n_outputs + (size_t)c->n_inputs + 1;
    double *block = arena_allocate(&sys->prepared_blocks,
                                   (widest + n_written) * sizeof(double) +
                                       n_ports * (sizeof(unsigned int) + sizeof(int)) +
                                       widest * sizeof(int),
                                   sizeof(double));
    if (block == NULL) {
        return -1;
    }
    d->step_block = block;
    d->real_scratch = block;
    d->inputs_written = block + widest;
    unsigned int *vr = (unsigned int *)(d->inputs_written + n_written);
    int *port = (int *)(vr + n_ports);
    d->int_scratch = port + n_ports;
    for (int type = SSX_REAL; type <= SSX_BOOLEAN; ++type) {
        fmu_port_batch *outputs = type == SSX_REAL ? &d->real_outputs
                                                   : &d->discrete_outputs[type - SSX_INTEGER];
        fmu_port_batch *inputs = type == SSX_REAL ? &d->real_inputs
                                                  : &d->discrete_inputs[type - SSX_INTEGER];
        build_batch(outputs, c->output_ports, c->n_outputs, (ssx_value_type)type, vr, port);
        vr += outputs->n;
        port += outputs->n;
        build_batch(inputs, c->input_ports, c->n_inputs, (ssx_value_type)type, vr, port);
        vr += inputs->n;
        port += inputs->n;
        d->has_discrete_ports |= type != SSX_REAL && outputs->n + inputs->n > 0;
    }
    build_batch(&d->text_outputs, c->output_ports, c->n_outputs, SSX_STRING, vr, port);
    vr += d->text_outputs.n;
    port += d->text_outputs.n;
    build_batch(&d->text_inputs, c->input_ports, c->n_inputs, SSX_STRING, vr, port);
    vr += d->text_inputs.n;
    port += d->text_inputs.n;
    build_batch(&d->binary_outputs, c->output_ports, c->n_outputs, SSX_BINARY, vr, port);
    vr += d->binary_outputs.n;
    port += d->binary_outputs.n;
    build_batch(&d->binary_inputs, c->input_ports, c->n_inputs, SSX_BINARY, vr, port);
    size_t n_texts = d->text_outputs.n > d->text_inputs.n ? d->text_outputs.n
                                                          : d->text_inputs.n;
    size_t n_binaries = d->binary_outputs.n > d->binary_inputs.n ? d->binary_outputs.n
                                                                 : d->binary_inputs.n;
    if (n_texts > 0) {
        d->text_scratch = calloc(n_texts, sizeof *d->text_scratch);
    }
    if (n_binaries > 0) {
        d->binary_scratch = calloc(n_binaries, sizeof *d->binary_scratch);
        d->size_scratch = calloc(n_binaries, sizeof *d->size_scratch);
    }
    if ((n_texts > 0 && d->text_scratch == NULL) ||
        (n_binaries > 0 && (d->binary_scratch == NULL || d->size_scratch == NULL))) {
        return fail_config(sys, c->index, -1, NAN,
                           "out of memory preparing the String and Binary ports of '%s'",
                           c->name);
    }
    d->inputs_written_epoch = -1;
    return 0;
}

void fmu_component_data_init(fmu_component_data *d, ssx_fmu *fmu)
{
    memset(d, 0, sizeof *d);
    d->fmu = fmu;
    d->inputs_written_epoch = -1;
    for (int slot = 0; slot < SSX_SNAPSHOT_SLOTS; ++slot) {
        d->fmu_state_generation[slot] = -1;
    }
}

/* FMU states stay with their (borrowed) instance, which releases them when it is freed. */
void fmu_component_data_free(fmu_component_data *d)
{
    free_prepared(d);
    restart_free(d->restart);
    d->restart = NULL;
}

int fmu_component_handle_events(ssx_system *sys, ssx_component *c, double t)
{
    fmu_component_data *d = fmu_data(c);
    if (d->restart == NULL) {
        return 0;
    }
    if (restart_handle(sys, c, d->fmu, d->restart, t) != 0) {
        return -1;
    }
    return fmu_component_read_outputs_at(sys, c, t);
}

int ssx_set_restart_handler(ssx_system *sys, int component, const ssx_fmu_experiment *experiment,
                            const ssx_fmu_values *starts, const unsigned int *vr,
                            const int *source, const double *scale, const double *offset,
                            size_t n)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (fmu_component_binding(c) == NULL) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s': a restart handler needs an FMU component", c->name);
    }
    for (size_t k = 0; k < n; ++k) {
        if (source[k] < 0 || source[k] >= c->n_outputs) {
            return fail_config(sys, component, -1, NAN,
                               "component '%s': a restart value reads output %d of %d", c->name,
                               source[k], c->n_outputs);
        }
    }
    fmu_component_data *d = fmu_data(c);
    restart_free(d->restart);
    d->restart = NULL;
    if (experiment == NULL) {
        return 0; /* removed */
    }
    d->restart = restart_new(sys, c, experiment, starts, vr, source, scale, offset, n);
    return d->restart != NULL ? 0 : -1;
}

/* The data itself is in the component's block (ssx_add_fmu_component). */
static void fmu_release(ssx_component *c)
{
    fmu_component_data_free(c->data);
}

int ssx_add_fmu_component(ssx_system *sys, const char *name, ssx_fmu *fmu, int can_get_set_state)
{
    if (fmu == NULL) {
        return fail_config(sys, -1, -1, NAN, "component '%s': no FMU given", name ? name : "?");
    }
    int index = system_add_component(sys, name, can_get_set_state, &ssx_fmu_component_ops,
                                     sizeof(fmu_component_data));
    if (index >= 0) {
        fmu_component_data_init(sys->components[index]->data, fmu);
    }
    return index;
}

int ssx_set_directional_derivatives(ssx_system *sys, int component, int provided)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (fmu_component_binding(c) == NULL) {
        return provided ? fail_config(sys, component, -1, NAN,
                                      "component '%s' is not an FMU component: it has no "
                                      "directional derivatives",
                                      c->name)
                        : 0;
    }
    fmu_data(c)->capabilities.directional_derivatives = provided != 0;
    return 0;
}

int ssx_set_interpolation(ssx_system *sys, int component, int can_interpolate_inputs,
                          int max_output_derivative_order)
{
    ssx_component *c = system_component(sys, component);
    if (c == NULL) {
        return -1;
    }
    if (max_output_derivative_order < 0) {
        return fail_config(sys, component, -1, NAN,
                           "component '%s': maxOutputDerivativeOrder %d is negative", c->name,
                           max_output_derivative_order);
    }
    if (fmu_component_binding(c) == NULL) {
        if (can_interpolate_inputs || max_output_derivative_order > 0) {
            return fail_config(sys, component, -1, NAN,
                               "component '%s' is not an FMU component: it neither "
                               "interpolates inputs nor has output derivatives",
                               c->name);
        }
        return 0;
    }
    fmu_component_data *d = fmu_data(c);
    d->capabilities.can_interpolate_inputs = can_interpolate_inputs != 0;
    d->capabilities.max_output_derivative_order = max_output_derivative_order;
    return 0;
}

/* ------------------------------------------------------------------ state by handle */

int fmu_state_save_into(ssx_system *sys, ssx_component *c, fmu_saved_state *s)
{
    fmu_component_data *d = fmu_data(c);
    *s = (fmu_saved_state){.fmu = d->fmu, .generation = ssx_fmu_generation(d->fmu)};
    int status = ssx_fmu_get_state(d->fmu, &s->fmu_state);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, sys->time, status, SLOT_GET_STATE);
}

int fmu_state_restore_from(ssx_system *sys, ssx_component *c, const fmu_saved_state *s, double t)
{
    fmu_component_data *d = fmu_data(c);
    if (s->fmu != d->fmu || s->generation != ssx_fmu_generation(d->fmu)) {
        return fail_config(sys, c->index, -1, t,
                           "component '%s': the saved state belongs to an earlier instance of "
                           "its FMU (instantiated again since); a serialized state can be "
                           "restored instead",
                           c->name);
    }
    int status = ssx_fmu_set_state(d->fmu, s->fmu_state);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, t, status, SLOT_SET_STATE);
}

void fmu_state_release(fmu_saved_state *s)
{
    if (s->fmu != NULL && s->fmu_state != NULL) {
        /* a state of an instance already freed went with it: nothing to free then */
        (void)ssx_fmu_free_state(s->fmu, &s->fmu_state);
    }
}

int fmu_state_write(ssx_system *sys, ssx_component *c, const fmu_saved_state *s,
                    byte_writer *out)
{
    fmu_component_data *d = fmu_data(c);
    size_t size = 0;
    int status = ssx_fmu_serialized_state_size(d->fmu, s->fmu_state, &size);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, sys->time, status, SLOT_SERIALIZED_STATE_SIZE);
    }
    write_u64(out, size);
    unsigned char *room = write_room(out, size);
    if (room == NULL) {
        return fail(sys, c->index, -1, sys->time, "out of memory serializing the state of '%s'",
                    c->name);
    }
    status = ssx_fmu_serialize_state(d->fmu, s->fmu_state, (char *)room, size);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, sys->time, status, SLOT_SERIALIZE_STATE);
}

int fmu_state_read(ssx_system *sys, ssx_component *c, byte_reader *in, fmu_saved_state *s)
{
    fmu_component_data *d = fmu_data(c);
    *s = (fmu_saved_state){.fmu = d->fmu, .generation = ssx_fmu_generation(d->fmu)};
    uint64_t size = read_u64(in);
    const unsigned char *bytes = size <= SIZE_MAX ? read_span(in, (size_t)size) : NULL;
    if (bytes == NULL) {
        return fail_config(sys, c->index, -1, sys->time,
                           "component '%s': the serialized state ends inside its FMU state",
                           c->name);
    }
    int status = ssx_fmu_deserialize_state(d->fmu, (const char *)bytes, (size_t)size,
                                           &s->fmu_state);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, sys->time, status, SLOT_DESERIALIZE_STATE);
}

static void *fmu_state_new(ssx_system *sys, ssx_component *c)
{
    fmu_saved_state *s = calloc(1, sizeof *s);
    if (s == NULL) {
        fail(sys, c->index, -1, sys->time, "out of memory saving the state of '%s'", c->name);
        return NULL;
    }
    return s;
}

static void fmu_state_free(void *state)
{
    if (state != NULL) {
        fmu_state_release(state);
        free(state);
    }
}

static void *fmu_save_state(ssx_system *sys, ssx_component *c)
{
    fmu_saved_state *s = fmu_state_new(sys, c);
    if (s != NULL && fmu_state_save_into(sys, c, s) != 0) {
        fmu_state_free(s);
        return NULL;
    }
    return s;
}

static int fmu_restore_state(ssx_system *sys, ssx_component *c, const void *state, double t)
{
    return fmu_state_restore_from(sys, c, state, t);
}

static int fmu_serialize_state(ssx_system *sys, ssx_component *c, const void *state,
                               byte_writer *out)
{
    return fmu_state_write(sys, c, state, out);
}

static void *fmu_deserialize_state(ssx_system *sys, ssx_component *c, byte_reader *in)
{
    fmu_saved_state *s = fmu_state_new(sys, c);
    if (s != NULL && fmu_state_read(sys, c, in, s) != 0) {
        fmu_state_free(s);
        return NULL;
    }
    return s;
}

static const component_state_ops fmu_saved_state_ops = {
    .save = fmu_save_state,
    .restore = fmu_restore_state,
    .free = fmu_state_free,
    .serialize = fmu_serialize_state,
    .deserialize = fmu_deserialize_state,
};

const ssx_component_ops ssx_fmu_component_ops = {
    .do_step = fmu_do_step,
    .write_inputs = fmu_write_inputs,
    .read_outputs = fmu_read_outputs,
    .evaluate_outputs = fmu_evaluate_outputs,
    .snapshot = fmu_snapshot,
    .restore = fmu_restore,
    .saved_state = &fmu_saved_state_ops,
    .release = fmu_release,
    .adopt_inputs = fmu_component_adopt_inputs,
    .initial_outputs = fmu_component_initial_outputs,
    .leave_initialization = fmu_component_leave_initialization,
    .directional_derivative = fmu_component_directional_derivative,
    .shared_with_threads = fmu_component_instance,
    .prepare = fmu_component_prepare,
    .unprepare = fmu_component_unprepare,
    .can_roll_back = fmu_component_can_roll_back,
    .capabilities = fmu_component_capabilities,
    .output_derivatives = fmu_component_output_derivatives,
    .set_input_derivatives = fmu_component_set_input_derivatives,
    .handle_events = fmu_component_handle_events,
    .tick_triggered_clock = fmu_tick_triggered_clock,
    .fmu = fmu_component_fmu,
    .checks_own_outputs = 1,
};
