/* The communication grid: t_k = t0 + k*dt by multiplication, the last point exactly tf. */
#include <math.h>

#include "test_support.h"

static void check_grid(double t0, double tf, double dt, size_t expected_samples)
{
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    CHECK(start_pendulum(fmu, t0, 0.5, 0.0, 0.0) == 0);
    ssx_system *sys = ssx_system_new("grid");
    add_pendulum(sys, "pendulum", fmu);
    CHECK_OK(sys, ssx_initialize(sys, t0));
    CHECK_OK(sys, ssx_run(sys, t0, tf, dt));

    size_t n = ssx_history_length(sys);
    const double *time = ssx_history_time(sys);
    const int *micro = ssx_history_micro(sys);
    CHECK(n == expected_samples);
    for (size_t k = 0; k + 1 < n; ++k) {
        CHECK(time[k] == t0 + (double)k * dt);
        CHECK(micro[k] == 0);
    }
    CHECK(time[n - 1] == tf);
    CHECK(ssx_time(sys) == tf);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

int main(void)
{
    /* 0.1 is not a binary fraction: accumulating t += dt would drift off 0.1 * k */
    check_grid(0.0, 1.0, 0.1, 11);
    check_grid(0.0, 1.0, 0.05, 21);
    /* 0.3 / 0.1 = 2.9999999999999996: no sliver step at the end */
    check_grid(0.0, 0.3, 0.1, 4);
    /* a shorter last step: 0.25 + 3 * 0.2 = 0.85 < 1 */
    check_grid(0.25, 1.0, 0.2, 5);
    /* tf == t0: only the initial sample */
    check_grid(0.5, 0.5, 0.1, 1);
    return 0;
}
