/* The whole system's state by handle (ssx_state_*): saved at t1, the run goes on to t2, the
 * state restored goes to t2 again with the same outputs and events; serialized, freed and
 * deserialized into a freshly built identical system, it goes on the same way; a state of
 * another layout is refused naming what differs; a component without FMU state is named. */
#include <math.h>

#include "test_support.h"

#define T1 0.3
#define T2 1.6
#define GRID_STEP 0.05

/* The seed's pendulum (the FMU of that stem) against a wall (restart handler), initialized at
 * 0 unless not asked. */
static ssx_system *wall_system(const char *stem, ssx_fmu **fmu, int initialize)
{
    *fmu = load_fmu(stem);
    int pendulum;
    ssx_system *sys = seed_pendulum_system(*fmu, SSX_ILLINOIS, 1e-9, 1e-9, &pendulum);
    add_wall_restart(sys, pendulum);
    if (initialize) {
        CHECK_OK(sys, ssx_initialize(sys, 0.0));
    }
    return sys;
}

/* Steps to t in stretches of GRID_STEP, through the events on the way. */
static void step_to(ssx_system *sys, double t)
{
    ssx_step_outcome out;
    do {
        CHECK_OK(sys, ssx_step_until(sys, t, GRID_STEP, &out));
    } while (out.time < t);
}

/* What the system reached: its outputs at the end and the events recorded from `first` on. */
typedef struct {
    double outputs[3];
    double events[4];
    size_t n_events;
    ssx_statistics stats;
} reached;

static reached reached_from(const ssx_system *sys, size_t first)
{
    reached r = {.n_events = ssx_event_count(sys) - first};
    CHECK(r.n_events <= 4);
    memcpy(r.outputs, ssx_outputs((ssx_system *)sys, 0), sizeof r.outputs);
    for (size_t k = 0; k < r.n_events; ++k) {
        ssx_event_record e;
        CHECK(ssx_event_get(sys, first + k, &e) == 0);
        r.events[k] = e.t;
    }
    ssx_get_statistics(sys, &r.stats);
    return r;
}

static void check_same(const reached *a, const reached *b)
{
    CHECK(memcmp(a->outputs, b->outputs, sizeof a->outputs) == 0);
    CHECK(a->n_events == b->n_events && a->n_events > 0);
    CHECK(memcmp(a->events, b->events, a->n_events * sizeof(double)) == 0);
    CHECK(a->stats.events == b->stats.events && a->stats.macro_steps == b->stats.macro_steps);
}

/* The explicit Euler pendulum keeps no integrator history beyond its state: stepping on from a
 * restored state is stepping on from the saved one, bit for bit. */
static void restore_repeats_the_run(void)
{
    ssx_fmu *fmu;
    ssx_system *sys = wall_system("pendulum_euler", &fmu, 1);
    step_to(sys, T1);
    ssx_system_state *state = ssx_state_save(sys);
    CHECK(state != NULL);
    size_t events_at_t1 = ssx_event_count(sys);
    step_to(sys, T2);
    reached first = reached_from(sys, events_at_t1);
    CHECK(first.n_events == 2); /* the wall hits at 1 and 3 quarter periods */
    CHECK_OK(sys, ssx_state_restore(sys, state));
    CHECK(ssx_time(sys) == T1);
    size_t events_before_again = ssx_event_count(sys); /* records are not rewound */
    step_to(sys, T2);
    reached again = reached_from(sys, events_before_again);
    check_same(&first, &again);
    /* a restore mid-step, right after an event, goes on the same way too */
    CHECK_OK(sys, ssx_state_restore(sys, state));
    ssx_step_outcome out;
    do {
        CHECK_OK(sys, ssx_step_until(sys, T2, GRID_STEP, &out));
    } while (!out.event);
    ssx_system_state *at_hit = ssx_state_save(sys);
    CHECK(at_hit != NULL);
    double hit = out.time;
    step_to(sys, T2);
    reached after_hit = reached_from(sys, ssx_event_count(sys) - 1);
    CHECK_OK(sys, ssx_state_restore(sys, at_hit));
    CHECK(ssx_time(sys) == hit);
    step_to(sys, T2);
    reached after_hit_again = reached_from(sys, ssx_event_count(sys) - 1);
    check_same(&after_hit, &after_hit_again);
    ssx_state_free(at_hit);
    ssx_state_free(state);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

/* CVODE starts afresh from a set state (it keeps its history only while nothing is set): the
 * run from a state restored in its own system is the reference, and differs from the run that
 * went on unrestored by the integrator's tolerance only. */
static void serialized_state_goes_on_in_a_new_system(void)
{
    ssx_fmu *fmu;
    ssx_system *sys = wall_system("pendulum_cvode", &fmu, 1);
    step_to(sys, T1);
    ssx_system_state *state = ssx_state_save(sys);
    CHECK(state != NULL);
    unsigned char *bytes;
    size_t size;
    CHECK_OK(sys, ssx_state_serialize(sys, state, &bytes, &size));
    CHECK(size > 8 && memcmp(bytes, "SSXSTATE", 8) == 0);
    size_t events_at_t1 = ssx_event_count(sys);
    step_to(sys, T2);
    reached unrestored = reached_from(sys, events_at_t1);
    CHECK_OK(sys, ssx_state_restore(sys, state));
    ssx_state_free(state);
    size_t events_before = ssx_event_count(sys);
    step_to(sys, T2);
    reached original = reached_from(sys, events_before);
    CHECK(original.n_events == 2 && unrestored.n_events == 2);
    for (size_t k = 0; k < 2; ++k) {
        CHECK_CLOSE(original.events[k], unrestored.events[k], 1e-9);
        CHECK_CLOSE(original.events[k], (2.0 * (double)k + 1.0) * PENDULUM_QUARTER_PERIOD,
                    1e-8);
    }
    CHECK_CLOSE(original.outputs[0], unrestored.outputs[0], 1e-8);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);

    ssx_fmu *fresh_fmu;
    ssx_system *fresh = wall_system("pendulum_cvode", &fresh_fmu, 1);
    /* cut short, or not a state at all: refused */
    CHECK(ssx_state_deserialize(fresh, bytes, size - 1) == NULL);
    CHECK(ssx_state_deserialize(fresh, (const unsigned char *)"not a state", 11) == NULL);
    CHECK_MESSAGE(fresh, "not a serialized syssimx system state");
    ssx_system_state *loaded = ssx_state_deserialize(fresh, bytes, size);
    CHECK(loaded != NULL);
    CHECK_OK(fresh, ssx_state_restore(fresh, loaded));
    CHECK(ssx_time(fresh) == T1);
    step_to(fresh, T2);
    reached continued = reached_from(fresh, 0);
    check_same(&original, &continued);
    ssx_state_free(loaded);
    ssx_system_free(fresh);
    ssx_fmu_free(fresh_fmu);

    /* another layout: a second pendulum named otherwise */
    ssx_fmu *other_fmu;
    ssx_system *other = wall_system("pendulum_cvode", &other_fmu, 0);
    ssx_fmu *second = load_fmu("pendulum_cvode");
    CHECK(start_pendulum(second, 0.0, 0.1, 0.0, 1e-10) == 0);
    add_pendulum(other, "Second", second);
    CHECK_OK(other, ssx_initialize(other, 0.0));
    CHECK(ssx_state_deserialize(other, bytes, size) == NULL);
    CHECK_MESSAGE(other, "has 2 components");
    ssx_state_bytes_free(bytes);
    ssx_system_free(other);
    ssx_fmu_free(second);
    ssx_fmu_free(other_fmu);
}

static void a_component_without_fmu_state_is_named(void)
{
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    CHECK(start_pendulum(fmu, 0.0, 0.5, 0.0, 1e-10) == 0);
    ssx_system *sys = ssx_system_new("no state");
    add_pendulum(sys, "Plain", fmu); /* declares it can get and set its state */
    ssx_fmu *stateless_fmu = load_fmu("pendulum_euler");
    CHECK(start_pendulum(stateless_fmu, 0.0, 0.5, 0.0, 0.0) == 0);
    CHECK(ssx_add_fmu_component(sys, "Stateless", stateless_fmu, 0) == 1);
    CHECK(ssx_state_save(sys) == NULL);
    CHECK_MESSAGE(sys, "not initialized");
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK(ssx_state_save(sys) == NULL);
    CHECK_MESSAGE(sys, "'Stateless' cannot save its state by handle");
    CHECK_MESSAGE(sys, "canGetAndSetFMUstate");
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
    ssx_fmu_free(stateless_fmu);
}

int main(void)
{
    restore_repeats_the_run();
    serialized_state_goes_on_in_a_new_system();
    a_component_without_fmu_state_is_named();
    return 0;
}
