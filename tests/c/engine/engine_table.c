/* Table sources: values between, at and outside the rows, a jump at a repeated time stamp,
 * held columns, a table driving an FMU, rollback in a hybrid run, and the errors. */
#include <math.h>
#include <string.h>

#include "test_support.h"

static const double TIME[] = {1.0, 2.0, 2.0, 4.0};
static const double RAMP[] = {0.0, 1.0, 5.0, 9.0};   /* jumps from 1 to 5 at t = 2 */
static const double COUNT[] = {3.0, 4.0, 7.0, 8.0};  /* integer: held */

static int add_table(ssx_system *sys)
{
    int table = ssx_add_table_component(sys, "u", TIME, 4);
    CHECK(table >= 0);
    CHECK(ssx_add_table_column(sys, table, SSX_REAL, 0, RAMP) == 0);
    CHECK(ssx_add_table_column(sys, table, SSX_INTEGER, 0, COUNT) == 1);
    CHECK(ssx_add_table_column(sys, table, SSX_REAL, 1, RAMP) == 2); /* the ramp held */
    return table;
}

static void values_on_a_grid(void)
{
    ssx_system *sys = ssx_system_new("table");
    int table = add_table(sys);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 5.0, 0.5));
    CHECK(ssx_history_length(sys) == 11);
    const double *t = ssx_history_time(sys);
    const double *v = ssx_history_values(sys, table);
    /* t:        0  0.5  1  1.5  2  2.5  3    3.5  4  4.5  5
     * ramp:     first row until 1, linear, right side of the jump at 2, last row after 4 */
    const double ramp[] = {0, 0, 0, 0.5, 5, 6, 7, 8, 9, 9, 9};
    const double count[] = {3, 3, 3, 3, 7, 7, 7, 7, 8, 8, 8};
    const double held[] = {0, 0, 0, 0, 5, 5, 5, 5, 9, 9, 9};
    for (int k = 0; k < 11; ++k) {
        CHECK(t[k] == 0.5 * k);
        CHECK(v[3 * k] == ramp[k]);
        CHECK(v[3 * k + 1] == count[k]);
        CHECK(v[3 * k + 2] == held[k]);
    }
    /* before the run starts, the value on the left of the jump; held columns take the row
     * before the time stamp (FMPy's rule for discrete inputs at initialization) */
    double values[3];
    CHECK_OK(sys, ssx_table_values(sys, table, 2.0, 0, values));
    CHECK(values[0] == 1.0 && values[1] == 3.0 && values[2] == 0.0);
    CHECK_OK(sys, ssx_initialize(sys, 2.0));
    CHECK(ssx_history_values(sys, table)[0] == 1.0);
    ssx_system_free(sys);
}

/* The ramp drives the pendulum's torque; an indicator on the ramp less 0.5 crosses zero at
 * t = 1.5 exactly, inside the step [1, 2]: locating it restores and re-steps the table with the
 * FMU. */
static void drives_an_fmu_and_rolls_back(void)
{
    static const double SHIFTED[] = {-0.5, 0.5, 4.5, 8.5};
    ssx_fmu *fmu = load_fmu("pendulum_euler");
    CHECK(start_pendulum(fmu, 0.0, 0.0, 0.0, 0.0) == 0);
    ssx_system *sys = ssx_system_new("table drives pendulum");
    int table = add_table(sys);
    CHECK(ssx_add_table_column(sys, table, SSX_REAL, 0, SHIFTED) == 3);
    int pendulum = add_pendulum(sys, "P", fmu);
    CHECK_OK(sys, ssx_connect(sys, table, 0, pendulum, 0, 1.0, 0.0));
    CHECK(ssx_add_indicator_output(sys, table, 3, 1) == 0);
    CHECK_OK(sys, ssx_set_hybrid_options(sys, 1e-10, 1e-9, 100, 10, 0, SSX_ILLINOIS, 0.0));
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 3.0, 1.0));
    CHECK(ssx_event_count(sys) == 1);
    ssx_event_record event;
    CHECK_OK(sys, ssx_event_get(sys, 0, &event));
    CHECK_CLOSE(event.t, 1.5, 1e-10);
    ssx_statistics stats;
    ssx_get_statistics(sys, &stats);
    CHECK(stats.state_restores >= 1);
    /* the grid plus the event before and after handling: the table's ramp at each */
    size_t n = ssx_history_length(sys);
    const double *t = ssx_history_time(sys);
    const double *v = ssx_history_values(sys, table);
    CHECK(n == 6);
    CHECK(t[2] == event.t && t[3] == event.t);
    CHECK_CLOSE(v[4 * 2], 0.5, 1e-9);
    CHECK(t[4] == 2.0 && v[4 * 4] == 5.0);
    CHECK(t[5] == 3.0 && v[4 * 5] == 7.0);
    ssx_system_free(sys);
    ssx_fmu_free(fmu);
}

static int contains(const ssx_system *sys, const char *text)
{
    return strstr(ssx_last_error(sys)->message, text) != NULL;
}

static void errors(void)
{
    ssx_system *sys = ssx_system_new("errors");
    const double backwards[] = {0.0, 2.0, 1.0};
    const double not_finite[] = {0.0, NAN};
    const double values[] = {1.0, 2.0, 3.0};
    CHECK(ssx_add_table_component(sys, "u", TIME, 0) == -1);
    CHECK(contains(sys, "table 'u': the table has no rows"));
    CHECK(ssx_add_table_component(sys, "u", backwards, 3) == -1);
    CHECK(contains(sys, "table 'u': the time goes back from 2 to 1 in row 2"));
    CHECK(ssx_add_table_component(sys, "u", not_finite, 2) == -1);
    CHECK(contains(sys, "table 'u': the time in row 1 is nan"));
    int table = ssx_add_table_component(sys, "u", values, 3);
    CHECK(table == 0);
    const double bad_column[] = {1.0, INFINITY, 0.0};
    CHECK(ssx_add_table_column(sys, table, SSX_REAL, 0, bad_column) == -1);
    CHECK(contains(sys, "table 'u': column 0 holds inf in row 1"));
    CHECK(ssx_add_python_component(sys, "py", 0) == 1);
    CHECK(ssx_add_table_column(sys, 1, SSX_REAL, 0, values) == -1);
    CHECK(contains(sys, "component 'py' is not a table source"));
    double out[1];
    CHECK(ssx_table_values(sys, 1, 0.0, 1, out) == -1);
    CHECK(contains(sys, "component 'py' is not a table source"));
    CHECK(ssx_add_output(sys, table, SSX_REAL, 0) == 0); /* an output without a column */
    CHECK(ssx_add_table_column(sys, table, SSX_REAL, 0, values) == -1);
    CHECK(contains(sys, "component 'u' is not a table source of its own columns"));
    ssx_system_free(sys);
}

int main(void)
{
    values_on_a_grid();
    drives_an_fmu_and_rolls_back();
    errors();
    return 0;
}
