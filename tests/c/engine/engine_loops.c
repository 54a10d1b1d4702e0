/* Algebraic loops between static components written as hooks (as Python components would be):
 * solutions against closed forms, scale/offset inside the loop, the error on a loop without
 * a solution, and a loop whose solution moves with time, which every recorded sample must
 * satisfy. */
#include <math.h>
#include <string.h>

#include "test_support.h"

typedef struct {
    ssx_system *sys;
    int component;
    double (*law)(double input);
} static_block;

static int evaluate(void *user, double t)
{
    (void)t;
    static_block *b = user;
    ssx_outputs(b->sys, b->component)[0] = b->law(ssx_inputs(b->sys, b->component)[0]);
    return 0;
}

static int step(void *user, double t, double dt)
{
    return evaluate(user, t + dt);
}

static int add_block(ssx_system *sys, const char *name, static_block *block,
                     double (*law)(double))
{
    int c = ssx_add_python_component(sys, name, 0);
    CHECK(c >= 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, 0) == 0);
    CHECK(ssx_add_input(sys, c, SSX_REAL, 0, 0.0) == 0);
    *block = (static_block){.sys = sys, .component = c, .law = law};
    ssx_hooks hooks = {.user = block, .do_step = step, .evaluate_outputs = evaluate};
    CHECK_OK(sys, ssx_set_hooks(sys, c, &hooks));
    return c;
}

static double falling_line(double u) { return 2.0 - 0.5 * u; }
static double rising_line(double u) { return 0.5 * u + 1.0; }
static double identity(double u) { return u; }
static double shifted(double u) { return u + 1.0; }

static ssx_system *loop_of(static_block blocks[2], double (*first)(double),
                           double (*second)(double), double scale, double offset)
{
    ssx_system *sys = ssx_system_new("loop");
    int a = add_block(sys, "A", &blocks[0], first);
    int b = add_block(sys, "B", &blocks[1], second);
    CHECK_OK(sys, ssx_connect(sys, a, 0, b, 0, 1.0, 0.0));
    CHECK_OK(sys, ssx_connect(sys, b, 0, a, 0, scale, offset));
    const int order[] = {a, b};
    const int sizes[] = {2};
    const int is_loop[] = {1};
    CHECK_OK(sys, ssx_set_schedule(sys, order, sizes, is_loop, 1));
    return sys;
}

static void linear_loop(void)
{
    static_block blocks[2];
    /* y_a = 2 - y_b / 2 and y_b = y_a / 2 + 1: y_a = 6/5, y_b = 8/5 */
    ssx_system *sys = loop_of(blocks, falling_line, rising_line, 1.0, 0.0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_CLOSE(ssx_outputs(sys, 0)[0], 1.2, 1e-12);
    CHECK_CLOSE(ssx_outputs(sys, 1)[0], 1.6, 1e-12);
    CHECK_CLOSE(ssx_inputs(sys, 0)[0], 1.6, 1e-12);
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.25));
    /* solved again at every communication point: each step sees the same fixed point */
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(stats.loop_solves == 1 + 4);
    CHECK(stats.loop_iterations >= 1); /* the start guess u = 0 is not the fixed point */
    const double *history = ssx_history_values(sys, 0);
    for (size_t k = 0; k < ssx_history_length(sys); ++k) {
        CHECK_CLOSE(history[k], 1.2, 1e-12);
    }
    ssx_system_free(sys);
}

static void nonlinear_loop_with_scale_and_offset(void)
{
    static_block blocks[2];
    /* u_a = y_b / 2 + 1/4, y_a = cos(u_a), y_b = y_a: y_a = cos(y_a / 2 + 1/4), a contraction
     * with one root, which scipy's brentq (xtol 1e-15) puts at 0.7969928434623472 */
    ssx_system *sys = loop_of(blocks, cos, identity, 0.5, 0.25);
    CHECK_OK(sys, ssx_set_loop_options(sys, 1e-13, 50, 1.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    double y = ssx_outputs(sys, 0)[0];
    CHECK_CLOSE(y, 0.7969928434623472, 1e-12);
    CHECK_CLOSE(ssx_inputs(sys, 0)[0], 0.5 * y + 0.25, 1e-12);
    ssx_system_free(sys);

    /* x = cos(x): the Dottie number */
    sys = loop_of(blocks, cos, identity, 1.0, 0.0);
    CHECK_OK(sys, ssx_set_loop_options(sys, 1e-13, 50, 0.7));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_CLOSE(ssx_outputs(sys, 0)[0], 0.7390851332151607, 1e-12);
    ssx_system_free(sys);
}

static void loop_without_solution(void)
{
    static_block blocks[2];
    /* u_a = y_a + 1 = u_a + 1: no solution */
    ssx_system *sys = loop_of(blocks, shifted, identity, 1.0, 0.0);
    CHECK_OK(sys, ssx_set_loop_options(sys, 1e-10, 20, 1.0));
    CHECK(ssx_initialize(sys, 0.0) == -1);
    const char *message = ssx_last_error(sys)->message;
    printf("%s\n", message);
    CHECK(strstr(message, "algebraic loop of components 'A', 'B' did not converge at t=0") !=
          NULL);
    CHECK(strstr(message, "residual norm 1") != NULL);
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_LOOP);
    ssx_system_free(sys);
}

/* A block whose law depends on time: y = t - u / 2, evaluated at the time the engine gives. */
typedef struct {
    ssx_system *sys;
    int component;
    double indicator_time; /* the callback indicator t - indicator_time */
} ramp_block;

static int ramp_evaluate(void *user, double t)
{
    ramp_block *b = user;
    ssx_outputs(b->sys, b->component)[0] = t - 0.5 * ssx_inputs(b->sys, b->component)[0];
    return 0;
}

static int ramp_step(void *user, double t, double dt)
{
    return ramp_evaluate(user, t + dt);
}

static int no_state(void *user, int slot)
{
    (void)user;
    (void)slot;
    return 0;
}

static int no_state_at(void *user, int slot, double t)
{
    (void)user;
    (void)slot;
    (void)t;
    return 0;
}

static int time_passed(void *user, double t, double *value)
{
    *value = t - ((ramp_block *)user)->indicator_time;
    return 0;
}

/* y_r = t - u_r / 2 and y_f = u_f closed through u_r = y_f, u_f = y_r: y_r = 2 t / 3. Both
 * blocks are stateless, so a snapshot holds nothing; with event_time > 0 an indicator on time
 * makes the hybrid path locate it (restoring and re-stepping the loop). */
static void time_varying_loop(ssx_coupling coupling, double event_time)
{
    ssx_system *sys = ssx_system_new("moving loop");
    ramp_block ramp = {.sys = sys, .indicator_time = event_time};
    static_block follower;
    int r = ssx_add_python_component(sys, "Ramp", 1);
    CHECK(r >= 0);
    CHECK(ssx_add_output(sys, r, SSX_REAL, 0) == 0);
    CHECK(ssx_add_input(sys, r, SSX_REAL, 0, 0.0) == 0);
    ramp.component = r;
    ssx_hooks ramp_hooks = {.user = &ramp, .do_step = ramp_step, .evaluate_outputs = ramp_evaluate,
                            .snapshot = no_state, .restore = no_state_at};
    CHECK_OK(sys, ssx_set_hooks(sys, r, &ramp_hooks));
    int f = ssx_add_python_component(sys, "Follower", 1);
    CHECK(f >= 0);
    CHECK(ssx_add_output(sys, f, SSX_REAL, 0) == 0);
    CHECK(ssx_add_input(sys, f, SSX_REAL, 0, 0.0) == 0);
    follower = (static_block){.sys = sys, .component = f, .law = identity};
    ssx_hooks follower_hooks = {.user = &follower, .do_step = step,
                                .evaluate_outputs = evaluate, .snapshot = no_state,
                                .restore = no_state_at};
    CHECK_OK(sys, ssx_set_hooks(sys, f, &follower_hooks));
    CHECK_OK(sys, ssx_connect(sys, r, 0, f, 0, 1.0, 0.0));
    CHECK_OK(sys, ssx_connect(sys, f, 0, r, 0, 1.0, 0.0));
    const int order[] = {r, f};
    const int sizes[] = {2};
    const int is_loop[] = {1};
    CHECK_OK(sys, ssx_set_schedule(sys, order, sizes, is_loop, 1));
    CHECK_OK(sys, ssx_set_coupling(sys, coupling));
    /* a residual below 1e-12 keeps the equations within 1e-10 with room to spare */
    CHECK_OK(sys, ssx_set_loop_options(sys, 1e-12, 50, 1.0));
    if (event_time > 0.0) {
        CHECK(ssx_add_indicator_callback(sys, r, time_passed, &ramp, 1) == 0);
    }
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.1));

    size_t n = ssx_history_length(sys);
    CHECK(n == (event_time > 0.0 ? 11u + 2u : 11u)); /* the event adds its two samples */
    const double *t = ssx_history_time(sys);
    const double *y_ramp = ssx_history_values(sys, r);
    const double *y_follower = ssx_history_values(sys, f);
    for (size_t k = 0; k < n; ++k) {
        CHECK_CLOSE(y_ramp[k], t[k] - 0.5 * y_follower[k], 1e-10);
        CHECK_CLOSE(y_follower[k], y_ramp[k], 1e-10);
        CHECK_CLOSE(y_ramp[k], 2.0 * t[k] / 3.0, 1e-10);
    }
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    if (event_time <= 0.0) {
        CHECK(stats.loop_solves == 1 + 10); /* once at t0, once per step */
    } else {
        CHECK(ssx_event_count(sys) == 1);
        CHECK(stats.localization_iterations > 0);
    }
    ssx_system_free(sys);
}

int main(void)
{
    linear_loop();
    time_varying_loop(SSX_GAUSS_SEIDEL, 0.0);
    time_varying_loop(SSX_JACOBI, 0.0);
    time_varying_loop(SSX_GAUSS_SEIDEL, 0.33);
    time_varying_loop(SSX_JACOBI, 0.33);
    nonlinear_loop_with_scale_and_offset();
    loop_without_solution();
    return 0;
}
