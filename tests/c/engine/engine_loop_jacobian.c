/* The gain/sum FMU loop with a unit conversion inside (y_gain [m] -> u_sum [cm], scale 100):
 * u_gain = b / (1 + 100 a c). Newton's Jacobian from fmi2GetDirectionalDerivative against the
 * same loop solved with finite differences. */
#include <math.h>
#include <string.h>

#include "test_support.h"

/* Value references of models/Gain and models/Sum */
enum { BLOCK_Y = 0, BLOCK_U = 1, GAIN_K = 2, SUM_B = 2, SUM_C = 3 };

static const double A = 1.5, B = 2.0, C = 0.02;

static void start_block(ssx_fmu *fmu, const unsigned int *vr, const double *values, size_t n)
{
    CHECK(start_fmu(fmu, 0.0, 0.0, vr, values, n) == 0);
}

static int add_block(ssx_system *sys, const char *name, ssx_fmu *fmu, int provided)
{
    int c = ssx_add_fmu_component(sys, name, fmu, 1);
    CHECK(c >= 0);
    CHECK(ssx_add_output(sys, c, SSX_REAL, BLOCK_Y) == 0);
    CHECK(ssx_add_input(sys, c, SSX_REAL, BLOCK_U, 0.0) == 0);
    CHECK_OK(sys, ssx_set_directional_derivatives(sys, c, provided));
    return c;
}

/* Runs the loop for ten steps; returns its statistics. */
static ssx_statistics solve(ssx_loop_jacobian mode, int provided, long *fmu_calls)
{
    ssx_fmu *gain = load_fmu("gain");
    ssx_fmu *sum = load_fmu("sum");
    const unsigned int gain_vr[] = {GAIN_K};
    const double gain_values[] = {A};
    const unsigned int sum_vr[] = {SUM_B, SUM_C};
    const double sum_values[] = {B, C};
    start_block(gain, gain_vr, gain_values, 1);
    start_block(sum, sum_vr, sum_values, 2);

    ssx_system *sys = ssx_system_new("gain-sum loop");
    int g = add_block(sys, "Gain", gain, provided);
    int s = add_block(sys, "Sum", sum, provided);
    CHECK_OK(sys, ssx_connect(sys, g, 0, s, 0, 100.0, 0.0));
    CHECK_OK(sys, ssx_connect(sys, s, 0, g, 0, 1.0, 0.0));
    const int order[] = {g, s};
    const int sizes[] = {2};
    const int is_loop[] = {1};
    CHECK_OK(sys, ssx_set_schedule(sys, order, sizes, is_loop, 1));
    CHECK_OK(sys, ssx_set_loop_jacobian(sys, mode));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 1.0, 0.1));

    double u_gain = B / (1.0 + 100.0 * A * C);
    const double *y_gain = ssx_history_values(sys, g);
    const double *y_sum = ssx_history_values(sys, s);
    CHECK(ssx_history_length(sys) == 11);
    for (size_t k = 0; k < ssx_history_length(sys); ++k) {
        CHECK_CLOSE(y_gain[k], A * u_gain, 1e-10);
        CHECK_CLOSE(y_sum[k], u_gain, 1e-10);
    }
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    ssx_fmu_counters gain_counters, sum_counters;
    ssx_fmu_get_counters(gain, &gain_counters);
    ssx_fmu_get_counters(sum, &sum_counters);
    *fmu_calls = gain_counters.directional_derivative + sum_counters.directional_derivative;
    ssx_system_free(sys);
    ssx_fmu_free(gain);
    ssx_fmu_free(sum);
    return stats;
}

static void a_python_component_has_no_directional_derivatives(void)
{
    ssx_system *sys = ssx_system_new("python");
    int c = ssx_add_python_component(sys, "P", 0);
    CHECK(ssx_set_directional_derivatives(sys, c, 1) == -1);
    CHECK(strstr(ssx_last_error(sys)->message, "not an FMU component") != NULL);
    CHECK(ssx_set_directional_derivatives(sys, c, 0) == 0);
    CHECK(ssx_set_loop_jacobian(sys, (ssx_loop_jacobian)7) == -1);
    ssx_system_free(sys);
}

int main(void)
{
    long analytic_calls, numeric_calls, undeclared_calls;
    ssx_statistics analytic = solve(SSX_JACOBIAN_AUTO, 1, &analytic_calls);
    ssx_statistics numeric = solve(SSX_JACOBIAN_FINITE_DIFFERENCES, 1, &numeric_calls);
    ssx_statistics undeclared = solve(SSX_JACOBIAN_AUTO, 0, &undeclared_calls);
    printf("Newton iterations: %ld with directional derivatives (%ld calls), %ld with finite "
           "differences\n",
           analytic.loop_iterations, analytic.directional_derivatives, numeric.loop_iterations);
    CHECK(analytic.loop_iterations >= 1);
    /* one call per unknown (Gain.u, Sum.u) per Newton iteration */
    CHECK(analytic.directional_derivatives == 2 * analytic.loop_iterations);
    CHECK(analytic_calls == analytic.directional_derivatives);
    CHECK(analytic.loop_iterations <= numeric.loop_iterations);
    CHECK(numeric.directional_derivatives == 0 && numeric_calls == 0);
    CHECK(undeclared.directional_derivatives == 0 && undeclared_calls == 0);
    a_python_component_has_no_directional_derivatives();
    return 0;
}
