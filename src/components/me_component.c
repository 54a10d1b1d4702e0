/* A Model Exchange FMU as a component: the engine integrates it with SUNDIALS CVODE (BDF,
 * Newton, dense linear solver) from communication point to communication point, its inputs held
 * over the step, and runs the Model Exchange state machine (FMI 2.0's and FMI 3.0's are the
 * same; the binding's back-end makes each call in its standard) around the integrator: event
 * indicators are CVODE's root functions, nextEventTime is a stop time, and after every
 * integrator step CompletedIntegratorStep may ask for event mode. The ticks of an FMI 3.0 FMU's
 * periodic input clocks are stop times too: event mode there, fmi3SetClock, then the discrete
 * states (a tick at the start time joins the event iteration after initialization). Each event
 * is handled at its
 * own time inside the step (NewDiscreteStates or UpdateDiscreteStates until nothing more is
 * needed) and reported as the component's own event, so no rollback is needed to find it.
 * Messages name each call as the FMU's standard does (ssx_fmu_function_name).
 *
 * CVODE stays warm (keeps its order, step size and history) from one communication point to
 * the next while nothing changed there: no input written, no event, no snapshot. Otherwise it
 * starts afresh from the state the engine holds, so every step that begins at a snapshot (in a
 * system with event indicators: every macro step) is a function of that state and the inputs
 * only, and the step taken again after a restore is the step taken the first time, bit for
 * bit; no snapshot needs CVODE's history. A fresh start costs accuracy (order 1 and an
 * estimated first step, so a local error of about the tolerance per communication step) and
 * time; a held input that changes is a discontinuity that needs the fresh start anyway.
 *
 * Each component has its own CVODE instance. Sharing one among uncoupled FMUs would make every
 * event of one restart the integration of all, let the stiffest set the step size and Newton
 * matrix of all, and tie components the master steps, restores and orders one by one. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "byte_stream.h"
#include "component_calls.h"
#include "component_setup.h"
#include "error.h"
#include "fmu_backend.h"
#include "fmu_binding.h"
#include "fmu_component.h"
#include "interrupt.h"
#include "own_events.h"
#include "system.h"
#include "zeno.h"

/* What the engine holds of the component's state besides the FMU state: the continuous
 * states, the pending time event and when and which way each event indicator last crossed (a
 * restore before a crossing forgets it, so a step taken again does not see its own event as a
 * repetition). */
typedef struct {
    double *x;
    ssx_fmu_event_info event;
    double *last_crossing; /* per event indicator, -INFINITY before any */
    /* per event indicator: +1 rising, -1 falling at its last crossing; 0 before any and once
     * that crossing's residue was taken (is_residue) */
    int *last_direction;
    /* the instant of the last tick of the FMU's periodic clocks made (the start time at first):
     * the next tick is the first after it, so no tick is skipped however short the steps */
    double last_tick;
} me_state;

typedef struct {
    fmu_component_data base; /* first: the data every FMU kind has (fmu_component.h) */
    size_t nx;         /* continuous states of the FMU */
    size_t nz;         /* event indicators */
    size_t n;          /* CVODE's states: nx, or one constant dummy when the FMU has none */
    double relative_tolerance; /* the instance's experiment tolerance, else the default */
    SUNContext context;
    void *cvode;       /* NULL when there is nothing to integrate (no states, no indicators) */
    int cvode_started; /* CVodeInit done */
    int *roots_found;  /* CVodeGetRootInfo's answer, per event indicator */
    N_Vector y;
    N_Vector absolute_tolerance;
    SUNMatrix matrix;
    SUNLinearSolver solver;
    double *nominals;
    me_state now;
    me_state saved[SSX_SNAPSHOT_SLOTS];
    long generation;   /* the start of the instance (ssx_fmu_starts) whose event iteration after
                        * initialization is done */
    /* where CVODE's history is valid to go on from (NAN: start afresh), and the FMU's values
     * epoch then (ssx_fmu_values_epoch: unchanged, no input was written) */
    double warm_at;
    long warm_epoch;
    ssx_component *c; /* for the callbacks */
    const int *allow_non_finite; /* the system's setting, read by the callbacks */
    /* set by a CVODE callback whose FMU call failed, reported when CVODE returns */
    long non_finite_indicator; /* -1, or the indicator that was NaN or infinite */
    long non_finite_derivative; /* -1, or the derivative that was NaN or infinite */
    double non_finite_value;
    int failed_status;
    const char *failed_call;
    double failed_time;
    char cvode_message[512];
} me_data;

static ssx_fmu *fmu_of(const ssx_component *c)
{
    return fmu_data(c)->fmu;
}

/* The name of the call in `slot` in the FMU's standard ("fmi3SetTime"). */
static const char *call_name(const ssx_component *c, ssx_fmu_slot slot)
{
    return ssx_fmu_function_name(fmu_of(c), (int)slot);
}

/* The call in `slot` of c's FMU returned `status` at t. */
static int fmi_failed(ssx_system *sys, const ssx_component *c, double t, int status,
                      ssx_fmu_slot slot)
{
    return fail_fmi(sys, c, fmu_of(c), t, status, call_name(c, slot));
}

/* ------------------------------------------------------------------ CVODE's callbacks */

static int callback_failed(me_data *me, int status, ssx_fmu_slot slot, double t)
{
    me->failed_status = status;
    me->failed_call = call_name(me->c, slot);
    me->failed_time = t;
    return -1; /* unrecoverable: CVODE stops and returns */
}

/* The FMU at time t with the states y (nothing to set for the dummy state). */
static int set_point(me_data *me, double t, N_Vector y)
{
    int status = ssx_fmu_set_time(me->base.fmu, t);
    if (!fmi_ok(status)) {
        return callback_failed(me, status, SLOT_SET_TIME, t);
    }
    if (me->nx > 0) {
        status = ssx_fmu_set_continuous_states(me->base.fmu, N_VGetArrayPointer(y), me->nx);
        if (!fmi_ok(status)) {
            return callback_failed(me, status, SLOT_SET_CONTINUOUS_STATES, t);
        }
    }
    return 0;
}

static int derivatives(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
{
    me_data *me = user;
    if (me->nx == 0) {
        N_VConst(0.0, ydot);
        return 0;
    }
    if (set_point(me, t, y) != 0) {
        return -1;
    }
    int status = ssx_fmu_get_derivatives(me->base.fmu, N_VGetArrayPointer(ydot), me->nx);
    if (!fmi_ok(status)) {
        return callback_failed(me, status, SLOT_GET_DERIVATIVES, t);
    }
    const double *dx = N_VGetArrayPointer(ydot);
    for (size_t i = 0; i < me->nx; ++i) {
        if (!isfinite(dx[i])) {
            /* unrecoverable: told to retry, CVODE shortens its steps towards the instant the
             * derivative turns NaN, ever shorter, without end */
            me->non_finite_derivative = (long)i;
            me->non_finite_value = dx[i];
            me->failed_time = t;
            return -1;
        }
    }
    return 0;
}

static int indicators(sunrealtype t, N_Vector y, sunrealtype *z, void *user)
{
    me_data *me = user;
    if (set_point(me, t, y) != 0) {
        return -1;
    }
    int status = ssx_fmu_get_event_indicators(me->base.fmu, z, me->nz);
    if (!fmi_ok(status)) {
        return callback_failed(me, status, SLOT_GET_EVENT_INDICATORS, t);
    }
    for (size_t i = 0; !*me->allow_non_finite && i < me->nz; ++i) {
        if (!isfinite(z[i])) { /* CVODE would never see it cross: the event would be lost */
            me->non_finite_indicator = (long)i;
            me->non_finite_value = z[i];
            me->failed_time = t;
            return -1;
        }
    }
    return 0;
}

static void cvode_error(int code, const char *module, const char *function, char *message,
                        void *user)
{
    (void)code;
    (void)module;
    me_data *me = user;
    snprintf(me->cvode_message, sizeof me->cvode_message, "%s: %s", function, message);
}

/* ------------------------------------------------------------------ failures */

static int fail_cvode(ssx_system *sys, ssx_component *c, me_data *me, double t, int flag,
                      const char *call)
{
    if (me->failed_call != NULL) {
        const char *failed = me->failed_call;
        me->failed_call = NULL;
        return fail_fmi(sys, c, fmu_of(c), me->failed_time, me->failed_status, failed);
    }
    if (me->non_finite_derivative >= 0) {
        long i = me->non_finite_derivative;
        me->non_finite_derivative = -1;
        return fail(sys, c->index, -1, me->failed_time,
                    "component '%s': derivative %ld (of %zu) is %g at t=%.17g: the integrator "
                    "cannot go on from a non-finite derivative",
                    c->name, i, me->nx, me->non_finite_value, me->failed_time);
    }
    if (me->non_finite_indicator >= 0) {
        long i = me->non_finite_indicator;
        me->non_finite_indicator = -1;
        return fail(sys, c->index, -1, me->failed_time,
                    "component '%s': event indicator %ld (of %zu) is %g at t=%.17g (non-finite "
                    "values stop the run unless they are allowed)",
                    c->name, i, me->nz, me->non_finite_value, me->failed_time);
    }
    return fail(sys, c->index, -1, t, "component '%s': %s failed at t=%.17g with %s%s%s",
                c->name, call, t, CVodeGetReturnFlagName(flag),
                me->cvode_message[0] ? ": " : "", me->cvode_message);
}

/* The FMU asked to end the simulation at t: the engine's termination path (see
 * ssx_termination); on a worker thread, the first request of its share. */
static void note_termination(ssx_system *sys, ssx_component *c, double t)
{
    ssx_termination *request = termination_record(sys);
    if (request->component < 0) {
        request->component = c->index;
        request->time = t;
        snprintf(request->message, sizeof request->message, "%s", ssx_fmu_last_message(fmu_of(c)));
    }
}

/* ... inside a step: reaching the step's end, the step counts as done. */
static int terminated(ssx_system *sys, ssx_component *c, double t, double t_end, double dt)
{
    note_termination(sys, c, t);
    if (t >= t_end - 1e-9 * dt) {
        return fmu_component_read_outputs_at(sys, c, t_end);
    }
    return fail(sys, c->index, -1, t,
                "component '%s' asked to stop at t=%.17g, inside the step to %.17g", c->name, t,
                t_end);
}

/* ------------------------------------------------------------------ event mode */

/* NewDiscreteStates (FMI 2.0) or UpdateDiscreteStates (FMI 3.0) until the FMU needs no more,
 * bounded: an FMU that never settles is chattering at t. */
static int iterate_discrete_states(ssx_system *sys, ssx_component *c, me_data *me, double t)
{
    ssx_fmu_event_info *info = &me->now.event;
    for (int round = 0;; ++round) {
        if (round > sys->hybrid.max_microsteps) {
            return fail_zeno(sys, c->index, -1, t,
                             "component '%s': %s still asked for new discrete states after %d "
                             "rounds at t=%.17g (max_microsteps)",
                             c->name, call_name(c, SLOT_NEW_DISCRETE_STATES),
                             sys->hybrid.max_microsteps, t);
        }
        int status = ssx_fmu_new_discrete_states(fmu_of(c), info);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, t, status, SLOT_NEW_DISCRETE_STATES);
        }
        if (!info->new_discrete_states_needed || info->terminate_simulation) {
            return 0;
        }
    }
}

/* The FMU's continuous states into the engine's copy: what a Python hook that restored or
 * re-initialized the FMU left there, too. */
static int read_states(ssx_system *sys, ssx_component *c, me_data *me, double t)
{
    if (me->nx == 0) {
        return 0;
    }
    int status = ssx_fmu_get_continuous_states(fmu_of(c), me->now.x, me->nx);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, t, status, SLOT_GET_CONTINUOUS_STATES);
}

/* Back to continuous-time mode after event mode: the states the event left and, when they
 * changed, their nominals (the absolute tolerances). */
static int leave_event_mode(ssx_system *sys, ssx_component *c, me_data *me, double t,
                            int read_nominals)
{
    int status = ssx_fmu_enter_continuous_time_mode(fmu_of(c));
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, SLOT_ENTER_CONTINUOUS_TIME_MODE);
    }
    if (read_states(sys, c, me, t) != 0) {
        return -1;
    }
    if (me->nx > 0 && (read_nominals || me->now.event.nominals_changed)) {
        status = ssx_fmu_get_nominals_of_continuous_states(fmu_of(c), me->nominals, me->nx);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, t, status, SLOT_GET_NOMINALS_OF_CONTINUOUS_STATES);
        }
        double *atol = N_VGetArrayPointer(me->absolute_tolerance);
        for (size_t i = 0; i < me->nx; ++i) {
            double nominal = fabs(me->nominals[i]);
            atol[i] = me->relative_tolerance * (nominal > 0.0 && isfinite(nominal) ? nominal : 1.0);
        }
        if (me->cvode_started &&
            CVodeSVtolerances(me->cvode, me->relative_tolerance, me->absolute_tolerance) !=
                CV_SUCCESS) {
            return fail(sys, c->index, -1, t, "component '%s': CVodeSVtolerances failed at "
                        "t=%.17g: %s", c->name, t, me->cvode_message);
        }
    }
    return 0;
}

/* One count the component was added with against the one the instance gives (FMI 3.0 asks
 * the instance; FMI 2.0 has no such call and the description's count is the only one). */
static int check_count(ssx_system *sys, ssx_component *c, double t, ssx_fmu_slot slot,
                       int (*ask)(ssx_fmu *, size_t *), size_t expected, const char *what)
{
    if (call_name(c, slot)[0] == '\0') {
        return 0;
    }
    size_t n = 0;
    int status = ask(fmu_of(c), &n);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, slot);
    }
    if (n != expected) {
        return fail(sys, c->index, -1, t,
                    "component '%s': %s: the instance has %zu (%s at t=%.17g), its "
                    "modelDescription declares %zu",
                    c->name, what, n, call_name(c, slot), t, expected);
    }
    return 0;
}

/* The event iteration FMI 2.0 and 3.0 require after ExitInitializationMode, once per
 * instance: the FMU may have been instantiated again (reinitialize) since the last step. */
static int start_instance(ssx_system *sys, ssx_component *c, me_data *me, double t)
{
    long generation = ssx_fmu_starts(fmu_of(c));
    if (me->generation == generation) {
        return 0;
    }
    if (check_count(sys, c, t, SLOT_GET_NUMBER_OF_CONTINUOUS_STATES,
                    ssx_fmu_get_number_of_continuous_states, me->nx, "continuous states") != 0 ||
        check_count(sys, c, t, SLOT_GET_NUMBER_OF_EVENT_INDICATORS,
                    ssx_fmu_get_number_of_event_indicators, me->nz, "event indicators") != 0) {
        return -1;
    }
    if (!ssx_fmu_experiment_tolerance(fmu_of(c), &me->relative_tolerance) ||
        !(me->relative_tolerance > 0.0)) {
        ssx_defaults defaults;
        ssx_get_defaults(&defaults);
        me->relative_tolerance = defaults.model_exchange_tolerance;
    }
    /* only an FMU with periodic clocks has ticks to make (and fmi3SetClock to make them) */
    int status = isfinite(ssx_fmu_next_clock_tick(fmu_of(c), -INFINITY))
                     ? ssx_fmu_tick_clocks(fmu_of(c), t)
                     : 0;
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, SLOT_SET_CLOCK);
    }
    me->now.last_tick = t;
    if (iterate_discrete_states(sys, c, me, t) != 0) {
        return -1;
    }
    if (me->now.event.terminate_simulation) {
        return fail(sys, c->index, -1, t, "component '%s' asked to terminate in its initial "
                    "event iteration at t=%.17g", c->name, t);
    }
    if (leave_event_mode(sys, c, me, t, 1) != 0) {
        return -1;
    }
    me->generation = generation;
    me->warm_at = NAN;
    for (size_t i = 0; i < me->nz; ++i) {
        me->now.last_crossing[i] = -INFINITY;
        me->now.last_direction[i] = 0;
    }
    return 0;
}

/* An event at t: event mode, the clocks that tick at `tick` (NAN: none; t within the grid's
 * rounding), the discrete states, continuous-time mode. The event is reported unless it is an
 * event's residue (the FMU still needs its event mode then: its discrete states may follow the
 * indicator's sign); a tick is reported as a tick of its own, after the event it coincides
 * with. */
static int handle_event(ssx_system *sys, ssx_component *c, me_data *me, double t,
                        ssx_own_event_kind kind, int report, double tick)
{
    int status = ssx_fmu_enter_event_mode(fmu_of(c));
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, SLOT_ENTER_EVENT_MODE);
    }
    if (!isnan(tick)) {
        status = ssx_fmu_tick_clocks(fmu_of(c), tick);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, t, status, SLOT_SET_CLOCK);
        }
        me->now.last_tick = tick;
    }
    if (iterate_discrete_states(sys, c, me, t) != 0) {
        return -1;
    }
    /* after a request to terminate the caller ends the run: no continuous-time mode */
    if (!me->now.event.terminate_simulation && leave_event_mode(sys, c, me, t, 0) != 0) {
        return -1;
    }
    if (report && own_event_report(sys, c, kind, t) != 0) {
        return -1;
    }
    return isnan(tick) ? 0 : own_event_report(sys, c, SSX_OWN_CLOCK_TICK, t);
}

/* ------------------------------------------------------------------ the step */

static int restart_cvode(ssx_system *sys, ssx_component *c, me_data *me, double t)
{
    if (me->nx > 0) {
        memcpy(N_VGetArrayPointer(me->y), me->now.x, me->nx * sizeof(double));
    }
    int flag = me->cvode_started ? CVodeReInit(me->cvode, t, me->y)
                                 : CVodeInit(me->cvode, derivatives, t, me->y);
    if (flag == CV_SUCCESS && !me->cvode_started) {
        me->cvode_started = 1;
        flag = CVodeSVtolerances(me->cvode, me->relative_tolerance, me->absolute_tolerance);
        if (flag == CV_SUCCESS) {
            flag = CVodeSetLinearSolver(me->cvode, me->solver, me->matrix);
        }
        if (flag == CV_SUCCESS && me->nz > 0) {
            flag = CVodeRootInit(me->cvode, (int)me->nz, indicators);
        }
    }
    return flag == CV_SUCCESS ? 0 : fail_cvode(sys, c, me, t, flag, "CVodeInit");
}

/* Too short a stretch for CVODE to start on (it refuses a stop time within rounding of t). */
static int negligible(double from, double to)
{
    return to - from <= 4.0 * DBL_EPSILON * fmax(fabs(from), fabs(to));
}

/* Integrates to `stop` or the first root or integrator step before it: *t is where it ended,
 * *root whether an indicator crossed there. The FMU holds the time and states at *t. */
static int integrate(ssx_system *sys, ssx_component *c, me_data *me, double stop, double *t,
                     int *root)
{
    *root = 0;
    if (me->cvode == NULL || negligible(*t, stop)) {
        *t = stop;
    } else {
        sunrealtype reached = *t;
        int flag = CVodeSetStopTime(me->cvode, stop);
        if (flag == CV_SUCCESS) {
            flag = CVode(me->cvode, stop, me->y, &reached, CV_ONE_STEP);
        }
        if (flag < 0) {
            return fail_cvode(sys, c, me, *t, flag, "CVode");
        }
        *root = flag == CV_ROOT_RETURN;
        *t = flag == CV_TSTOP_RETURN ? stop : reached;
        if (me->nx > 0) {
            memcpy(me->now.x, N_VGetArrayPointer(me->y), me->nx * sizeof(double));
        }
    }
    int status = ssx_fmu_set_time(fmu_of(c), *t);
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, *t, status, SLOT_SET_TIME);
    }
    if (me->nx > 0) {
        status = ssx_fmu_set_continuous_states(fmu_of(c), me->now.x, me->nx);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, *t, status, SLOT_SET_CONTINUOUS_STATES);
        }
    }
    return 0;
}

/* A crossing back the way the indicator came, within the interval of two distinct events
 * after its last crossing, is that event's residue, not an event of its own: an FMU that
 * leaves its indicator a hair past zero after the event (FMUSDK's bouncing ball puts the ball
 * slightly below the floor) sees it cross back as the state moves away. One residue per
 * event: a third crossing that close is chattering again. */
static int is_residue(const ssx_system *sys, const me_state *state, size_t i, int direction,
                      double interval)
{
    return state->last_direction[i] != 0 && direction == -state->last_direction[i] &&
           interval < distinct_events_interval(&sys->hybrid);
}

/* Chattering, by the rule of the master's indicators (zeno.h), with no grid to resolve: the
 * engine's integrator resolves every crossing. Near an accumulation point (a ball whose
 * bounces never end) CVODE would soon miss a crossing and let the state sink through: the run
 * ends here instead. *residue: every crossing at t is a residue (is_residue). */
static int state_event_chatters(ssx_system *sys, ssx_component *c, me_data *me, double t,
                                int *residue)
{
    if (CVodeGetRootInfo(me->cvode, me->roots_found) != CV_SUCCESS) {
        return fail(sys, c->index, -1, t, "component '%s': CVodeGetRootInfo failed at t=%.17g",
                    c->name, t);
    }
    *residue = 1;
    for (size_t i = 0; i < me->nz; ++i) {
        if (me->roots_found[i] == 0) {
            continue;
        }
        double interval = t - me->now.last_crossing[i];
        if (is_residue(sys, &me->now, i, me->roots_found[i], interval)) {
            me->now.last_direction[i] = 0;
            continue;
        }
        *residue = 0;
        me->now.last_crossing[i] = t;
        me->now.last_direction[i] = me->roots_found[i];
        if (zeno_judge(&sys->hybrid, interval, INFINITY, 0.0) != ZENO_NONE) {
            return fail_zeno(sys, c->index, -1, t,
                             "component '%s': its event indicator %zu crossed again at t=%.17g, "
                             "only %.3g after its previous crossing: chattering (Zeno) "
                             "behaviour; the minimum interval is %.3g",
                             c->name, i, t, interval, zeno_min_interval(&sys->hybrid));
        }
    }
    return 0;
}

/* Time and step events at one instant, more than max_microsteps in a row: the FMU keeps asking
 * for events without time going on. */
static int events_stall(ssx_system *sys, ssx_component *c, double t, double *last, int *repeated)
{
    *repeated = t == *last ? *repeated + 1 : 0;
    *last = t;
    if (*repeated <= sys->hybrid.max_microsteps) {
        return 0;
    }
    return fail_zeno(sys, c->index, -1, t,
                     "component '%s' asked for %d events at t=%.17g without time going on "
                     "(max_microsteps): chattering (Zeno) behaviour",
                     c->name, *repeated + 1, t);
}

static int me_do_step(ssx_system *sys, ssx_component *c, double t, double dt)
{
    me_data *me = c->data;
    if (start_instance(sys, c, me, t) != 0) {
        return -1;
    }
    double t_end = t + dt;
    double now = t;
    double last_event = -INFINITY;
    int repeated_events = 0;
    /* a time event within the grid's rounding of the step's end belongs to this step */
    double reach = t_end + 1e-9 * dt;
    int warm = me->warm_at == t && me->warm_epoch == ssx_fmu_values_epoch(fmu_of(c));
    me->warm_at = NAN;
    if (me->cvode != NULL && !warm &&
        (read_states(sys, c, me, t) != 0 || restart_cvode(sys, c, me, t) != 0)) {
        return -1;
    }
    int event_at_end = 0;
    while (now < t_end) {
        const ssx_fmu_event_info *event = &me->now.event;
        double tick = ssx_fmu_next_clock_tick(fmu_of(c), me->now.last_tick);
        /* the instants of the due time event and clock tick inside the step, else INFINITY */
        double event_at = event->next_event_time_defined && event->next_event_time <= reach
                              ? fmin(fmax(event->next_event_time, now), t_end)
                              : INFINITY;
        double tick_at = tick <= reach ? fmin(fmax(tick, now), t_end) : INFINITY;
        double stop = fmin(t_end, fmin(event_at, tick_at));
        int root;
        if (run_interrupted(sys, now) != 0 || integrate(sys, c, me, stop, &now, &root) != 0) {
            return -1;
        }
        int enter_event_mode = 0, terminate = 0;
        int status = ssx_fmu_completed_integrator_step(fmu_of(c), !sys->stepping_hybrid,
                                                       &enter_event_mode, &terminate);
        if (!fmi_ok(status)) {
            return fmi_failed(sys, c, now, status, SLOT_COMPLETED_INTEGRATOR_STEP);
        }
        if (terminate) {
            return terminated(sys, c, now, t_end, dt);
        }
        int time_event = now >= event_at, clock_tick = now >= tick_at;
        if (!(root || time_event || clock_tick || enter_event_mode)) {
            continue;
        }
        ssx_own_event_kind kind = root         ? SSX_OWN_STATE_EVENT
                                  : time_event ? SSX_OWN_TIME_EVENT
                                               : SSX_OWN_STEP_EVENT;
        int residue = 0;
        if ((root ? state_event_chatters(sys, c, me, now, &residue)
                  : events_stall(sys, c, now, &last_event, &repeated_events)) != 0) {
            return -1;
        }
        /* a tick alone is reported as the tick only */
        int report = root ? !(residue && !time_event && !enter_event_mode)
                          : time_event || enter_event_mode;
        if (handle_event(sys, c, me, now, kind, report, clock_tick ? tick : NAN) != 0) {
            return -1;
        }
        if (me->now.event.terminate_simulation) {
            return terminated(sys, c, now, t_end, dt);
        }
        event_at_end = now >= t_end;
        if (me->cvode != NULL && !event_at_end && restart_cvode(sys, c, me, now) != 0) {
            return -1;
        }
    }
    if (!event_at_end) {
        me->warm_at = t_end;
        me->warm_epoch = ssx_fmu_values_epoch(fmu_of(c));
    }
    return fmu_component_read_outputs_at(sys, c, t_end);
}

/* ------------------------------------------------------------------ ports and snapshots */

/* New input values are an event of the environment: FMI 2.0 lets discrete inputs change only
 * in event mode, and what the FMU computes from them is settled by its event iteration. Held
 * over the step, they are a discontinuity CVODE starts afresh after anyway. */
static int me_write_inputs(ssx_system *sys, ssx_component *c)
{
    me_data *me = c->data;
    double t = sys->time;
    if (fmu_component_inputs_unchanged(c)) {
        return 0;
    }
    if (start_instance(sys, c, me, t) != 0) {
        return -1;
    }
    int status = ssx_fmu_enter_event_mode(fmu_of(c));
    if (!fmi_ok(status)) {
        return fmi_failed(sys, c, t, status, SLOT_ENTER_EVENT_MODE);
    }
    if (ssx_fmu_component_ops.write_inputs(sys, c) != 0 ||
        iterate_discrete_states(sys, c, me, t) != 0) {
        return -1;
    }
    if (me->now.event.terminate_simulation) {
        note_termination(sys, c, t);
        return fail(sys, c->index, -1, t,
                    "component '%s' asked to stop at t=%.17g when its inputs changed", c->name,
                    t);
    }
    return leave_event_mode(sys, c, me, t, 0);
}

static int me_read_outputs(ssx_system *sys, ssx_component *c)
{
    if (start_instance(sys, c, c->data, sys->time) != 0) {
        return -1;
    }
    return ssx_fmu_component_ops.read_outputs(sys, c);
}

static int me_evaluate_outputs(ssx_system *sys, ssx_component *c, double t)
{
    if (start_instance(sys, c, c->data, t) != 0 || me_write_inputs(sys, c) != 0) {
        return -1;
    }
    return fmu_component_read_outputs_at(sys, c, t);
}

static void copy_state(const me_data *me, me_state *to, const me_state *from)
{
    to->event = from->event;
    to->last_tick = from->last_tick;
    memcpy(to->x, from->x, me->n * sizeof(double));
    if (me->nz > 0) {
        memcpy(to->last_crossing, from->last_crossing, me->nz * sizeof(double));
        memcpy(to->last_direction, from->last_direction, me->nz * sizeof(int));
    }
}

static int me_snapshot(ssx_system *sys, ssx_component *c, int slot)
{
    me_data *me = c->data;
    if (ssx_fmu_component_ops.snapshot(sys, c, slot) != 0) {
        return -1;
    }
    me->warm_at = NAN; /* the step from here must be the one a restore here would take */
    copy_state(me, &me->saved[slot], &me->now);
    return 0;
}

static int me_restore(ssx_system *sys, ssx_component *c, int slot, double t)
{
    me_data *me = c->data;
    me->warm_at = NAN;
    if (ssx_fmu_component_ops.restore(sys, c, slot, t) != 0) {
        return -1;
    }
    copy_state(me, &me->now, &me->saved[slot]);
    if (me->nx == 0) {
        return 0;
    }
    /* the engine's copy is the state: the FMU holds it whatever its own state kept */
    int status = ssx_fmu_set_continuous_states(fmu_of(c), me->now.x, me->nx);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, t, status, SLOT_SET_CONTINUOUS_STATES);
}

/* ------------------------------------------------------------------ life cycle */

static void me_free(me_data *me)
{
    if (me == NULL) {
        return;
    }
    if (me->cvode != NULL) {
        CVodeFree(&me->cvode);
    }
    if (me->solver != NULL) {
        SUNLinSolFree(me->solver);
    }
    if (me->matrix != NULL) {
        SUNMatDestroy(me->matrix);
    }
    if (me->y != NULL) {
        N_VDestroy(me->y);
    }
    if (me->absolute_tolerance != NULL) {
        N_VDestroy(me->absolute_tolerance);
    }
    if (me->context != NULL) {
        SUNContext_Free(&me->context);
    }
    fmu_component_data_free(&me->base);
    free(me->nominals);
    free(me->roots_found);
    free(me->now.x);
    free(me->now.last_crossing);
    free(me->now.last_direction);
    for (int slot = 0; slot < SSX_SNAPSHOT_SLOTS; ++slot) {
        free(me->saved[slot].x);
        free(me->saved[slot].last_crossing);
        free(me->saved[slot].last_direction);
    }
    free(me);
}

static void me_release(ssx_component *c)
{
    me_free(c->data);
    c->data = NULL;
}

/* ------------------------------------------------------------------ state by handle */

/* The FMU's state and the engine's copy of the continuous states, events and crossings. */
typedef struct {
    fmu_saved_state fmu;
    me_state engine;
} me_saved_state;

static void me_state_free(void *state)
{
    me_saved_state *s = state;
    if (s == NULL) {
        return;
    }
    fmu_state_release(&s->fmu);
    free(s->engine.x);
    free(s->engine.last_crossing);
    free(s->engine.last_direction);
    free(s);
}

static int state_new(me_state *state, size_t n, size_t nz);

static me_saved_state *me_state_new(ssx_system *sys, ssx_component *c)
{
    const me_data *me = c->data;
    me_saved_state *s = calloc(1, sizeof *s);
    if (s == NULL || state_new(&s->engine, me->n, me->nz) != 0) {
        me_state_free(s);
        fail(sys, c->index, -1, sys->time, "out of memory saving the state of '%s'", c->name);
        return NULL;
    }
    return s;
}

static void *me_save_state(ssx_system *sys, ssx_component *c)
{
    me_data *me = c->data;
    me_saved_state *s = me_state_new(sys, c);
    if (s == NULL || fmu_state_save_into(sys, c, &s->fmu) != 0) {
        me_state_free(s);
        return NULL;
    }
    copy_state(me, &s->engine, &me->now);
    return s;
}

static int me_restore_state(ssx_system *sys, ssx_component *c, const void *state, double t)
{
    me_data *me = c->data;
    const me_saved_state *s = state;
    me->warm_at = NAN;
    if (fmu_state_restore_from(sys, c, &s->fmu, t) != 0) {
        return -1;
    }
    copy_state(me, &me->now, &s->engine);
    if (me->nx == 0) {
        return 0;
    }
    int status = ssx_fmu_set_continuous_states(fmu_of(c), me->now.x, me->nx);
    return fmi_ok(status) ? 0 : fmi_failed(sys, c, t, status, SLOT_SET_CONTINUOUS_STATES);
}

static int me_serialize_state(ssx_system *sys, ssx_component *c, const void *state,
                              byte_writer *out)
{
    const me_data *me = c->data;
    const me_saved_state *s = state;
    if (fmu_state_write(sys, c, &s->fmu, out) != 0) {
        return -1;
    }
    write_doubles(out, s->engine.x, me->n);
    write_bytes(out, &s->engine.event, sizeof s->engine.event);
    write_doubles(out, &s->engine.last_tick, 1);
    write_doubles(out, s->engine.last_crossing, me->nz);
    write_bytes(out, s->engine.last_direction, me->nz * sizeof(int));
    return out->failed ? fail(sys, c->index, -1, sys->time,
                              "out of memory serializing the state of '%s'", c->name)
                       : 0;
}

static void *me_deserialize_state(ssx_system *sys, ssx_component *c, byte_reader *in)
{
    const me_data *me = c->data;
    me_saved_state *s = me_state_new(sys, c);
    if (s == NULL || fmu_state_read(sys, c, in, &s->fmu) != 0) {
        me_state_free(s);
        return NULL;
    }
    read_doubles(in, s->engine.x, me->n);
    read_bytes(in, &s->engine.event, sizeof s->engine.event);
    read_doubles(in, &s->engine.last_tick, 1);
    read_doubles(in, s->engine.last_crossing, me->nz);
    read_bytes(in, s->engine.last_direction, me->nz * sizeof(int));
    if (in->failed) {
        me_state_free(s);
        fail_config(sys, c->index, -1, sys->time,
                    "component '%s': the serialized state ends inside its integrator's state",
                    c->name);
        return NULL;
    }
    return s;
}

static const component_state_ops me_saved_state_ops = {
    .save = me_save_state,
    .restore = me_restore_state,
    .free = me_state_free,
    .serialize = me_serialize_state,
    .deserialize = me_deserialize_state,
};

const ssx_component_ops ssx_model_exchange_component_ops = {
    .do_step = me_do_step,
    .write_inputs = me_write_inputs,
    .read_outputs = me_read_outputs,
    .evaluate_outputs = me_evaluate_outputs,
    .snapshot = me_snapshot,
    .restore = me_restore,
    .saved_state = &me_saved_state_ops,
    .release = me_release,
    .adopt_inputs = fmu_component_adopt_inputs,
    .initial_outputs = fmu_component_initial_outputs,
    .leave_initialization = fmu_component_leave_initialization,
    .directional_derivative = fmu_component_directional_derivative,
    .shared_with_threads = fmu_component_instance,
    .prepare = fmu_component_prepare,
    .unprepare = fmu_component_unprepare,
    .can_roll_back = fmu_component_can_roll_back,
    .capabilities = fmu_component_capabilities,
    .handle_events = fmu_component_handle_events,
    .fmu = fmu_component_fmu,
    .checks_own_outputs = 1,
};

static int state_new(me_state *state, size_t n, size_t nz)
{
    state->x = calloc(n, sizeof *state->x);
    state->last_crossing = malloc((nz + 1) * sizeof *state->last_crossing);
    state->last_direction = calloc(nz + 1, sizeof *state->last_direction);
    if (state->x == NULL || state->last_crossing == NULL || state->last_direction == NULL) {
        return -1;
    }
    for (size_t i = 0; i < nz; ++i) {
        state->last_crossing[i] = -INFINITY;
    }
    state->last_tick = -INFINITY;
    return 0;
}

/* CVODE with its vectors, dense matrix and linear solver; NULL when out of memory. */
static me_data *me_new(ssx_fmu *fmu, size_t nx, size_t nz)
{
    me_data *me = calloc(1, sizeof *me);
    if (me == NULL) {
        return NULL;
    }
    fmu_component_data_init(&me->base, fmu);
    me->nx = nx;
    me->nz = nz;
    me->n = nx > 0 ? nx : 1;
    me->generation = -1;
    me->warm_at = NAN;
    me->nominals = calloc(me->n, sizeof *me->nominals);
    me->roots_found = calloc(nz + 1, sizeof *me->roots_found);
    int ok = me->nominals != NULL && me->roots_found != NULL &&
             state_new(&me->now, me->n, nz) == 0;
    for (int slot = 0; slot < SSX_SNAPSHOT_SLOTS; ++slot) {
        ok = ok && state_new(&me->saved[slot], me->n, nz) == 0;
    }
    if (!ok || (nx == 0 && nz == 0)) {
        /* nothing to integrate: time events and step completion only */
        if (ok) {
            return me;
        }
        me_free(me);
        return NULL;
    }
    ok = SUNContext_Create(NULL, &me->context) == 0 &&
         (me->y = N_VNew_Serial((sunindextype)me->n, me->context)) != NULL &&
         (me->absolute_tolerance = N_VNew_Serial((sunindextype)me->n, me->context)) != NULL &&
         (me->cvode = CVodeCreate(CV_BDF, me->context)) != NULL &&
         (me->matrix = SUNDenseMatrix((sunindextype)me->n, (sunindextype)me->n, me->context)) !=
             NULL &&
         (me->solver = SUNLinSol_Dense(me->y, me->matrix, me->context)) != NULL;
    if (!ok) {
        me_free(me);
        return NULL;
    }
    /* the dummy state of an FMU without states never changes: any tolerance does */
    N_VConst(1.0, me->y);
    N_VConst(1.0, me->absolute_tolerance);
    return me;
}

/* The callbacks' data and the error handler (the linear solver follows CVodeInit). */
static int configure_cvode(me_data *me)
{
    return CVodeSetUserData(me->cvode, me) == CV_SUCCESS &&
                   CVodeSetErrHandlerFn(me->cvode, cvode_error, me) == CV_SUCCESS &&
                   CVodeSetNoInactiveRootWarn(me->cvode) == CV_SUCCESS
               ? 0
               : -1;
}

int ssx_add_model_exchange_component(ssx_system *sys, const char *name, ssx_fmu *fmu,
                                     int can_get_set_state, int n_states,
                                     int n_event_indicators)
{
    const char *label = name != NULL ? name : "?";
    if (fmu == NULL || !ssx_fmu_is_model_exchange(fmu)) {
        return fail_config(sys, -1, -1, NAN,
                           "component '%s': %s", label,
                           fmu == NULL ? "no FMU given"
                                       : "the FMU was not loaded for Model Exchange "
                                         "(ssx_fmu_load with SSX_MODEL_EXCHANGE)");
    }
    if (n_states < 0 || n_event_indicators < 0) {
        return fail_config(sys, -1, -1, NAN,
                           "component '%s': %d continuous states and %d event indicators; "
                           "neither can be negative",
                           label, n_states, n_event_indicators);
    }
    me_data *me = me_new(fmu, (size_t)n_states, (size_t)n_event_indicators);
    if (me == NULL || (me->cvode != NULL && configure_cvode(me) != 0)) {
        me_free(me);
        return fail_config(sys, -1, -1, NAN, "component '%s': out of memory creating CVODE",
                           label);
    }
    int index =
        system_add_component(sys, name, can_get_set_state, &ssx_model_exchange_component_ops,
                             0);
    if (index < 0) {
        me_free(me);
        return -1;
    }
    ssx_component *c = sys->components[index];
    me->c = c;
    me->allow_non_finite = &sys->allow_non_finite;
    me->non_finite_indicator = -1;
    me->non_finite_derivative = -1;
    c->data = me;
    return index;
}
