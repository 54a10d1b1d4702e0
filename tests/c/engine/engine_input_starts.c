/* Input starts: a finite start is written to an unconnected FMU input; NaN (no value set by the
 * user) keeps the FMU's own value, read once the FMU is initialized. keep_defaults holds
 * u = h_min = 1e-7 (its modelDescription declares 0.000000), y = u / h_min. */
#include <math.h>
#include <string.h>

#include "test_support.h"

enum { KEEP_Y = 0, KEEP_U = 1 };

static ssx_system *keep_defaults_system(ssx_fmu *fmu, double u_start)
{
    CHECK(start_fmu(fmu, 0.0, 0.0, NULL, NULL, 0) == 0);
    ssx_system *sys = ssx_system_new("input starts");
    int c = ssx_add_fmu_component(sys, "K", fmu, 1);
    CHECK(ssx_add_output(sys, c, SSX_REAL, KEEP_Y) == 0);
    CHECK(ssx_add_input(sys, c, SSX_REAL, KEEP_U, u_start) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.1, 0.05));
    return sys;
}

int main(void)
{
    ssx_fmu *fmu = load_fmu("keep_defaults");

    ssx_system *own = keep_defaults_system(fmu, NAN);
    CHECK(ssx_inputs(own, 0)[0] == 1e-7);
    CHECK(ssx_outputs(own, 0)[0] == 1.0);
    ssx_system_free(own);

    ssx_system *written = keep_defaults_system(fmu, 3e-7);
    CHECK(ssx_inputs(written, 0)[0] == 3e-7);
    CHECK(ssx_outputs(written, 0)[0] == 3.0);
    ssx_system_free(written);

    ssx_system *sys = ssx_system_new("refused starts");
    int python = ssx_add_python_component(sys, "Py", 0);
    CHECK(ssx_add_input(sys, python, SSX_REAL, 0, NAN) == -1);
    CHECK(strstr(ssx_last_error(sys)->message, "FMU components only") != NULL);
    int k = ssx_add_fmu_component(sys, "K", fmu, 1);
    CHECK(ssx_add_input(sys, k, SSX_REAL, KEEP_U, INFINITY) == -1);
    ssx_system_free(sys);

    ssx_fmu_free(fmu);
    return 0;
}
