/* Built-in behaviour of an FMU component: its fmi2 calls, batched by value type, and what the
 * statuses of a step mean. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "fmi2Functions.h"

#include "component.h"
#include "error.h"
#include "fmu_binding.h"
#include "parallel_step.h"
#include "system.h"

/* Reads every output; a failure is reported at t, the time the FMU is at. */
static int read_outputs_at(ssx_system *sys, ssx_component *c, double t)
{
    /* x - x is 0 for a finite x and NaN for NaN and infinities: one subtraction per value
     * instead of a classification (Integer and Boolean values are always finite) */
    double residue = 0.0;
    const ssx_port_batch *real = &c->output_batch[SSX_REAL];
    if (real->n > 0) {
        int status = ssx_fmu_get_real(c->fmu, real->vr, real->n, c->real_scratch);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, t, status, "fmi2GetReal");
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
            return fail_fmi(sys, c, t, status,
                            type == SSX_INTEGER ? "fmi2GetInteger" : "fmi2GetBoolean");
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
    return read_outputs_at(sys, c, sys->time);
}

/* Whether the FMU already holds every input value: nothing set it since the engine's last write
 * (connected inputs change each step; unconnected ones only when Python writes them). */
static int inputs_unchanged(const ssx_component *c)
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

static int fmu_write_inputs(ssx_system *sys, ssx_component *c)
{
    if (inputs_unchanged(c)) {
        return 0;
    }
    const ssx_port_batch *real = &c->input_batch[SSX_REAL];
    if (real->n > 0) {
        for (size_t i = 0; i < real->n; ++i) {
            c->real_scratch[i] = c->inputs[real->port[i]];
        }
        int status = ssx_fmu_set_real(c->fmu, real->vr, real->n, c->real_scratch);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, sys->time, status, "fmi2SetReal");
        }
    }
    for (int type = SSX_INTEGER; type <= SSX_BOOLEAN; ++type) {
        const ssx_port_batch *b = &c->input_batch[type];
        if (b->n == 0) {
            continue;
        }
        for (size_t i = 0; i < b->n; ++i) {
            double value = c->inputs[b->port[i]];
            /* integers round to nearest: a scaled connection may land a hair off an integer */
            c->int_scratch[i] = type == SSX_BOOLEAN ? (value != 0.0)
                                                    : (int)(value < 0 ? value - 0.5 : value + 0.5);
        }
        int status = type == SSX_INTEGER
                         ? ssx_fmu_set_integer(c->fmu, b->vr, b->n, c->int_scratch)
                         : ssx_fmu_set_boolean(c->fmu, b->vr, b->n, c->int_scratch);
        if (!fmi_ok(status)) {
            return fail_fmi(sys, c, sys->time, status,
                            type == SSX_INTEGER ? "fmi2SetInteger" : "fmi2SetBoolean");
        }
    }
    if (c->n_inputs > 0) {
        memcpy(c->inputs_written, c->inputs, (size_t)c->n_inputs * sizeof(double));
    }
    c->inputs_written_epoch = ssx_fmu_values_epoch(c->fmu);
    return 0;
}

/* fmi2Discard means one of two things. The FMU asks to end the simulation (fmi2Terminated):
 * the request is kept for the run to end cleanly, and the step counts as done when the FMU
 * reached its end. Otherwise the FMU could not complete the step: a failure that says how far
 * it got (fmi2LastSuccessfulTime). */
static int discarded_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    double t_end = t + dt;
    char log[sizeof sys->termination.message];
    snprintf(log, sizeof log, "%s", ssx_fmu_last_message(c->fmu)); /* before queries overwrite it */
    int terminated = 0;
    double reached = NAN;
    int asked = ssx_fmu_get_terminated(c->fmu, &terminated);
    if (!fmi_ok(ssx_fmu_get_last_successful_time(c->fmu, &reached))) {
        reached = NAN;
    }
    if (!fmi_ok(asked) || !terminated) {
        char got_to[96] = "fmi2GetRealStatus(fmi2LastSuccessfulTime) failed";
        if (!isnan(reached)) {
            snprintf(got_to, sizeof got_to, "fmi2LastSuccessfulTime=%.17g", reached);
        }
        return fail_status(sys, c, isnan(reached) ? t : reached, fmi2Discard,
                           "component '%s': fmi2DoStep from t=%.17g to %.17g returned "
                           "fmi2Discard without asking to terminate: the FMU completed the step "
                           "only up to %s%s%s%s",
                           c->name, t, t_end, got_to, log[0] ? " (FMU log: " : "", log,
                           log[0] ? ")" : " (the FMU logged no message)");
    }
    double stop = isnan(reached) ? t : reached;
    /* the first request of the run counts; on a worker thread, the first of its share */
    ssx_termination *request = parallel_termination_slot(sys);
    if (request->component < 0) {
        request->component = c->index;
        request->time = stop;
        snprintf(request->message, sizeof request->message, "%s", log);
    }
    /* the grid's own rounding: a remainder below 1e-9 steps is the step's end */
    if (reached >= t_end - 1e-9 * dt) {
        return read_outputs_at(sys, c, t_end);
    }
    return fail(sys, c->index, -1, t,
                "component '%s' asked to stop at t=%.17g, inside the step from %.17g to %.17g",
                c->name, stop, t, t_end);
}

static int fmu_do_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    /* In hybrid mode the engine may set an earlier state again, so it must not promise not to. */
    int status = ssx_fmu_do_step(c->fmu, t, dt, !sys->stepping_hybrid);
    if (status == fmi2Discard) {
        return discarded_step(sys, c, t, dt);
    }
    if (!fmi_ok(status)) {
        return fail_fmi(sys, c, t, status, "fmi2DoStep");
    }
    return read_outputs_at(sys, c, t + dt);
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
        return fail_fmi(sys, c, sys->time, status, "fmi2GetFMUstate");
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
        return fail_fmi(sys, c, t, status, "fmi2SetFMUstate");
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
                            type == SSX_REAL      ? "fmi2GetReal"
                            : type == SSX_INTEGER ? "fmi2GetInteger"
                                                  : "fmi2GetBoolean");
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
