/* Built-in behaviour of an FMU component: its FMI calls, batched by value type, what the
 * statuses of a step mean, and the events an FMI 3.0 FMU handles in its own step. */
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "component.h"
#include "error.h"
#include "fmu_backend.h"
#include "fmu_binding.h"
#include "input_order.h"
#include "parallel_step.h"
#include "system.h"

/* The status every standard gives a step it could not complete (fmi2Discard, fmi3Discard). */
enum { STATUS_DISCARD = 2, STATUS_ERROR = 3 };

/* The standard's name of the call in `slot` of c's FMU, for messages. */
static const char *call_name(const ssx_component *c, ssx_fmu_slot slot)
{
    return ssx_fmu_function_name(c->fmu, (int)slot);
}

int fmu_component_read_outputs_at(ssx_system *sys, ssx_component *c, double t)
{
    /* x - x is 0 for a finite x and NaN for NaN and infinities: one subtraction per value
     * instead of a classification (Integer and Boolean values are always finite) */
    double residue = 0.0;
    const ssx_port_batch *real = &c->output_batch[SSX_REAL];
    if (real->n > 0) {
        int status = ssx_fmu_get_real(c->fmu, real->vr, real->n, c->real_scratch);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, t, status, call_name(c, SLOT_GET_REAL));
        }
        for (size_t i = 0; i < real->n; ++i) {
            double value = c->real_scratch[i];
            c->outputs[real->port[i]] = value;
            residue += value - value;
        }
    }
    for (int type = SSX_INTEGER; type <= SSX_BOOLEAN; ++type) {
        const ssx_port_batch *b = &c->output_batch[type];
        if (b->n == 0) {
            continue;
        }
        int status = type == SSX_INTEGER
                         ? ssx_fmu_get_integer(c->fmu, b->vr, b->n, c->int_scratch)
                         : ssx_fmu_get_boolean(c->fmu, b->vr, b->n, c->int_scratch);
        if (!fmi_ok(status)) {
            ssx_fmu_slot slot = type == SSX_INTEGER ? SLOT_GET_INTEGER : SLOT_GET_BOOLEAN;
            return fail_fmi(sys, c, t, status, call_name(c, slot));
        }
        for (size_t i = 0; i < b->n; ++i) {
            int value = c->int_scratch[i];
            c->outputs[b->port[i]] = type == SSX_BOOLEAN ? (value != 0) : (double)value;
        }
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
    if (c->inputs_written_epoch != ssx_fmu_values_epoch(c->fmu)) {
        return 0;
    }
    for (int i = 0; i < c->n_inputs; ++i) {
        if (c->inputs[i] != c->inputs_written[i]) {
            return 0;
        }
    }
    return 1;
}

/* An Integer input's value is an int at the FMU boundary; one beyond it cannot be written. */
static int integer_out_of_range(ssx_system *sys, ssx_component *c, unsigned int vr, double value)
{
    const char *name = ssx_fmu_variable_name(c->fmu, vr);
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
    return input_order_write(sys, c);
}

static int write_values(ssx_system *sys, ssx_component *c)
{
    const ssx_port_batch *real = &c->input_batch[SSX_REAL];
    if (real->n > 0) {
        for (size_t i = 0; i < real->n; ++i) {
            c->real_scratch[i] = c->inputs[real->port[i]];
        }
        int status = ssx_fmu_set_real(c->fmu, real->vr, real->n, c->real_scratch);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, sys->time, status, call_name(c, SLOT_SET_REAL));
        }
    }
    for (int type = SSX_INTEGER; type <= SSX_BOOLEAN; ++type) {
        const ssx_port_batch *b = &c->input_batch[type];
        if (b->n == 0) {
            continue;
        }
        for (size_t i = 0; i < b->n; ++i) {
            double value = c->inputs[b->port[i]];
            if (type == SSX_INTEGER && !(value > INT_MIN - 0.5 && value < INT_MAX + 0.5)) {
                return integer_out_of_range(sys, c, b->vr[i], value);
            }
            /* integers round to nearest: a scaled connection may land a hair off an integer */
            c->int_scratch[i] = type == SSX_BOOLEAN ? (value != 0.0)
                                                    : (int)(value < 0 ? value - 0.5 : value + 0.5);
        }
        int status = type == SSX_INTEGER
                         ? ssx_fmu_set_integer(c->fmu, b->vr, b->n, c->int_scratch)
                         : ssx_fmu_set_boolean(c->fmu, b->vr, b->n, c->int_scratch);
        if (!fmi_ok(status)) {
            ssx_fmu_slot slot = type == SSX_INTEGER ? SLOT_SET_INTEGER : SLOT_SET_BOOLEAN;
            return fail_fmi(sys, c, sys->time, status, call_name(c, slot));
        }
    }
    if (c->n_inputs > 0) {
        memcpy(c->inputs_written, c->inputs, (size_t)c->n_inputs * sizeof(double));
    }
    c->inputs_written_epoch = ssx_fmu_values_epoch(c->fmu);
    return 0;
}

/* The FMU asked to end the simulation at `reached` during the step from t to t_end: the request
 * is kept for the run to end cleanly, and the step counts as done when the FMU reached its end. */
static int stop_requested(ssx_system *sys, ssx_component *c, double t, double t_end,
                          double reached, const char *log)
{
    double stop = isnan(reached) ? t : reached;
    /* the first request of the run counts; on a worker thread, the first of its share */
    ssx_termination *request = parallel_termination_slot(sys);
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
    char log[sizeof sys->termination.message];
    snprintf(log, sizeof log, "%s", ssx_fmu_last_message(c->fmu)); /* before queries overwrite it */
    int terminated = 0;
    double reached = NAN;
    int asked = ssx_fmu_get_terminated(c->fmu, &terminated);
    if (!fmi_ok(ssx_fmu_get_last_successful_time(c->fmu, &reached))) {
        reached = NAN;
    }
    if (!fmi_ok(asked) || !terminated) {
        ssx_step_outcome outcome;
        ssx_fmu_step_outcome(c->fmu, &outcome);
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
                           ssx_fmu_status_text(c->fmu, STATUS_DISCARD), got_to,
                           log[0] ? " (FMU log: " : "", log,
                           log[0] ? ")" : " (the FMU logged no message)");
    }
    return stop_requested(sys, c, t, t_end, reached, log);
}

/* One doStep from t to t_end and what its status means; the outcome of a completed call is
 * left in *outcome. 1: the call completed; 0: the step is over (the FMU asked to stop, or the
 * call failed: the return of `done` says which). */
static int step_call(ssx_system *sys, ssx_component *c, double t, double t_end,
                     ssx_step_outcome *outcome, int *done)
{
    /* In hybrid mode the engine may set an earlier state again, so it must not promise not to. */
    int status = ssx_fmu_do_step(c->fmu, t, t_end - t, !sys->stepping_hybrid);
    if (status == STATUS_DISCARD) {
        *done = discarded_step(sys, c, t, t_end);
        return 0;
    }
    if (!fmi_ok(status)) {
        *done = fail_fmi(sys, c, t, status, call_name(c, SLOT_DO_STEP));
        return 0;
    }
    ssx_fmu_step_outcome(c->fmu, outcome);
    return 1;
}

/* An event the FMU found at t_e and handled in event mode: its discrete states are updated
 * until they settle (more rounds than max_microsteps is chattering), then it steps again.
 * *terminate is set when the FMU asks to end the simulation there. */
static int handle_own_event(ssx_system *sys, ssx_component *c, double t_e, int *terminate)
{
    int status = ssx_fmu_enter_event_mode(c->fmu);
    if (!fmi_ok(status)) {
        return fail_fmi(sys, c, t_e, status, call_name(c, SLOT_ENTER_EVENT_MODE));
    }
    ssx_fmu_event_info update = {.new_discrete_states_needed = 1};
    for (int round = 0; update.new_discrete_states_needed && !update.terminate_simulation;
         ++round) {
        if (round == sys->hybrid.max_microsteps) {
            return fail_zeno(sys, c->index, -1, t_e,
                             "component '%s': %s still asked for another round after %d rounds "
                             "at t=%.17g (chattering; max_microsteps=%d)",
                             c->name, call_name(c, SLOT_NEW_DISCRETE_STATES), round, t_e,
                             sys->hybrid.max_microsteps);
        }
        status = ssx_fmu_new_discrete_states(c->fmu, &update);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, t_e, status, call_name(c, SLOT_NEW_DISCRETE_STATES));
        }
    }
    *terminate = update.terminate_simulation;
    if (!*terminate) {
        status = ssx_fmu_enter_step_mode(c->fmu);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, t_e, status, call_name(c, SLOT_ENTER_STEP_MODE));
        }
    }
    return own_event_report(sys, c, SSX_OWN_FMU_EVENT, t_e);
}

/* The rest of an FMI 3.0 step that returned early, needs its events handled or asks to stop:
 * each event is handled at the time the FMU returned (or at the step's end) and reported as the
 * component's own, and the FMU steps on from there until the step's end. No rollback: the FMU
 * knows the time of its events. */
static int step_on(ssx_system *sys, ssx_component *c, double t, double t_end,
                   ssx_step_outcome outcome)
{
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
        if (!terminate && outcome.event_handling_needed &&
            handle_own_event(sys, c, reached, &terminate) != 0) {
            return -1;
        }
        if (terminate) {
            return stop_requested(sys, c, t, t_end, reached, ssx_fmu_last_message(c->fmu));
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
    ssx_step_outcome outcome;
    int done = 0;
    if (!step_call(sys, c, t, t + dt, &outcome, &done)) {
        return done;
    }
    if (outcome.early_return || outcome.event_handling_needed || outcome.terminate_simulation) {
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
    long generation = ssx_fmu_generation(c->fmu);
    if (c->fmu_state_generation[slot] != generation) {
        c->fmu_state[slot] = NULL; /* released with its instance by the binding */
        c->fmu_state_generation[slot] = generation;
    }
    int status = ssx_fmu_get_state(c->fmu, &c->fmu_state[slot]);
    if (!fmi_ok(status)) {
        return fail_fmi(sys, c, sys->time, status, call_name(c, SLOT_GET_STATE));
    }
    return 0;
}

static int fmu_restore(ssx_system *sys, ssx_component *c, int slot, double t)
{
    /* a restore is followed by stepping again, which a component that asked to stop refuses */
    if (sys->termination.component >= 0) {
        return fail(sys, c->index, -1, t,
                    "component '%s' asked to stop at t=%.17g: the system is not stepped again",
                    sys->components[sys->termination.component]->name, sys->termination.time);
    }
    if (c->fmu_state[slot] == NULL ||
        c->fmu_state_generation[slot] != ssx_fmu_generation(c->fmu)) {
        return fail(sys, c->index, -1, t,
                    "component '%s': no FMU state in snapshot slot %d for the live instance "
                    "(was the FMU instantiated again after the snapshot?)",
                    c->name, slot);
    }
    int status = ssx_fmu_set_state(c->fmu, c->fmu_state[slot]);
    if (!fmi_ok(status)) {
        return fail_fmi(sys, c, t, status, call_name(c, SLOT_SET_STATE));
    }
    return 0;
}

/* An input the user never set keeps the FMU's own value: the declared start may be a rounded
 * print of it (exporters write 1e-7 as 0.000000), so writing the start could change the model.
 * Reading the value lets the engine treat the input like any other. */
int fmu_component_adopt_inputs(ssx_system *sys, ssx_component *c, double t0)
{
    for (int k = 0; k < c->n_inputs; ++k) {
        if (c->input_driver[k] >= 0 || !isnan(c->input_starts[k])) {
            continue;
        }
        unsigned int vr = c->input_ports[k].vr;
        ssx_value_type type = c->input_ports[k].type;
        double real = 0.0;
        int integer = 0;
        int status = type == SSX_REAL      ? ssx_fmu_get_real(c->fmu, &vr, 1, &real)
                     : type == SSX_INTEGER ? ssx_fmu_get_integer(c->fmu, &vr, 1, &integer)
                                           : ssx_fmu_get_boolean(c->fmu, &vr, 1, &integer);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, t0, status,
                            call_name(c, type == SSX_REAL      ? SLOT_GET_REAL
                                         : type == SSX_INTEGER ? SLOT_GET_INTEGER
                                                               : SLOT_GET_BOOLEAN));
        }
        c->inputs[k] = type == SSX_REAL ? real : type == SSX_BOOLEAN ? (integer != 0) : integer;
    }
    return 0;
}

const ssx_component_ops ssx_fmu_component_ops = {
    .do_step = fmu_do_step,
    .write_inputs = fmu_write_inputs,
    .read_outputs = fmu_read_outputs,
    .evaluate_outputs = fmu_evaluate_outputs,
    .snapshot = fmu_snapshot,
    .restore = fmu_restore,
};
