/* Plans (ssx_plan_*): a text with every record reads and writes back byte for byte; every
 * refusal names its line, record and field; the seed's pendulum against a wall, built from a
 * plan with no FMU given (the builder loads it from an unpacked folder), hits the wall at the
 * quarter period, as the Python-built system does. */
#define _XOPEN_SOURCE 700 /* mkdtemp, symlink */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "engine_test_fmus.h"
#include "test_support.h"

/* Every record kind once at least, as the writer writes it. */
static const char every_record[] =
    "syssimx-plan 1\n"
    "system \"all \\\"records\\\"\\\\ \\n\\t\\x01\\x7f \xc3\xa9\"\n"
    "experiment 0 1 0.05\n"
    "fmu \"A\" 1 2 \"a\" \"model_a\" \"{guid}\" \"\" 0\n"
    "model_exchange \"B\" 0 2 1 3 \"/abs/b\" \"model_b\" \"token\" \"B\" 1\n"
    "table \"T\" 3 0 0.5 1\n"
    "table_column 2 real 0 3 1 2 -inf\n"
    "table_column 2 integer 1 3 1 2 3\n"
    "python \"Py\" 1\n"
    "fmu_experiment 0 1 1e-06 0 0\n"
    "start 0 real 7 0.5\n"
    "start 0 integer 8 -3\n"
    "start 0 boolean 9 1\n"
    "start 1 string 10 \"text\"\n"
    "start 1 binary 11 \"\\x00\\xff\"\n"
    "isolated 0 2.5\n"
    "fmi3_variables 1 1 0\n"
    "fmi3_variable 1 0 float64 \"x\"\n"
    "fmi3_element 1 1000 int32 \"v[1]\" 5 1 3 nan\n"
    "fmi3_intermediate 1 0\n"
    "fmi3_clock 1 9 0.1 0\n"
    "output 0 real 0\n"
    "output 1 boolean 1\n"
    "input 0 real 4 nan\n"
    "input 1 string 5 \"start\"\n"
    "input 3 real 0 1.5\n"
    "connect 0 0 3 0 2 -273.15\n"
    "indicator_output 0 0 -1\n"
    "indicator_callback 3 1\n"
    "indicator_slope 0 2\n"
    "subscribe indicator 0 0\n"
    "subscribe own_events 1 3\n"
    "restart_handler 0 1 1e-10 0 0 1 11 1e-10 1 8 2 1 9 0 2 7 0 1 0 8 0 -0.8 0\n"
    "schedule 2 2 1 0 1 2 0 2 3\n"
    "coupling jacobi\n"
    "threads 2\n"
    "calling_thread_only 0 1\n"
    "loop_options 1e-10 100 1\n"
    "loop_jacobian finite_differences\n"
    "directional_derivatives 0 1\n"
    "interpolation 0 1 1\n"
    "input_order 2\n"
    "extrapolate_held_inputs 1\n"
    "step_control 1 1 0.0001 0.0001 1e-09 0 0 0.9 0.2 5 0 0.2 0.15 0\n"
    "power_bonds 1 0 0 3 0\n"
    "hybrid_options 1e-09 1e-09 100 10 1 illinois_unguarded 0\n"
    "allow_non_finite 1\n"
    "output_interval 4\n"
    "run_output_interval 0\n"
    "history 1\n";

static void round_trip(void)
{
    char error[512];
    ssx_plan *plan = ssx_plan_read(every_record, sizeof every_record - 1, error, sizeof error);
    if (plan == NULL) {
        fprintf(stderr, "refused: %s\n", error);
    }
    CHECK(plan != NULL);
    size_t size = 0;
    char *text = ssx_plan_write(plan, &size);
    CHECK(text != NULL && size == sizeof every_record - 1);
    if (strcmp(text, every_record) != 0) {
        fprintf(stderr, "written:\n%s\n", text);
    }
    CHECK(strcmp(text, every_record) == 0);
    CHECK(ssx_plan_component_count(plan) == 4);
    CHECK(strcmp(ssx_plan_component_name(plan, 3), "Py") == 0);
    CHECK(ssx_plan_port_count(plan, 2, 0) == 2 && ssx_plan_port_count(plan, 0, 1) == 1);
    ssx_value_type type;
    unsigned int vr;
    CHECK(ssx_plan_port(plan, 1, 1, 0, &type, &vr) == 0 && type == SSX_STRING && vr == 5);
    CHECK(ssx_plan_port(plan, 2, 0, 1, &type, &vr) == 0 && type == SSX_INTEGER);
    CHECK(ssx_plan_port(plan, 0, 0, 1, &type, &vr) == -1);
    double start, stop, step;
    CHECK(ssx_plan_experiment(plan, &start, &stop, &step) == 0 && stop == 1.0 && step == 0.05);
    ssx_plan_text_free(text);
    ssx_plan_free(plan);

    /* comments, blank lines, other spellings of the numbers, CR LF: read as the same plan,
     * written in the writer's form */
    const char loose[] = "syssimx-plan 1\r\n# a comment\n\n  system \"s\"   # named\r\n"
                         "experiment 0.0 1e0 5e-2\n";
    plan = ssx_plan_read(loose, sizeof loose - 1, error, sizeof error);
    CHECK(plan != NULL);
    text = ssx_plan_write(plan, &size);
    CHECK(strcmp(text, "syssimx-plan 1\nsystem \"s\"\nexperiment 0 1 0.05\n")
          == 0);
    ssx_plan_text_free(text);
    ssx_plan_free(plan);
}

/* The hex form of `count` doubles, as the format writes a long list ("xN:" and 16 lowercase
 * digits a value, least significant byte first), into text. */
static void hex_list(char *text, const double *values, size_t count)
{
    text += sprintf(text, "x%zu:", count);
    for (size_t k = 0; k < count; ++k) {
        uint64_t bits;
        memcpy(&bits, &values[k], sizeof bits);
        for (int byte = 0; byte < 8; ++byte) {
            text += sprintf(text, "%02x", (unsigned int)(bits >> (8 * byte)) & 0xffu);
        }
    }
}

/* A list of more than 64 doubles is written in its hex form, exact to the bit (a NaN's payload,
 * -0, the smallest subnormal), and read back to the same text; 64 stay decimal. */
static void hex_round_trip(void)
{
    enum { ROWS = 65 };
    double times[ROWS], column[ROWS];
    char decimal[4096] = "syssimx-plan 1\nsystem \"s\"\ntable \"t\" 65";
    for (int k = 0; k < ROWS; ++k) {
        times[k] = k * 0.1;
        column[k] = k;
        sprintf(decimal + strlen(decimal), " %.17g", times[k]);
    }
    uint64_t payload = 0x7ff8000000000abcu;
    memcpy(&column[1], &payload, sizeof payload);
    column[2] = -0.0;
    column[3] = 4.9406564584124654e-324;
    column[4] = -INFINITY;
    column[5] = 1.0 / 3.0;
    strcat(decimal, "\n");
    char expected[8192] = "syssimx-plan 1\nsystem \"s\"\ntable \"t\" ";
    hex_list(expected + strlen(expected), times, ROWS);
    strcat(expected, "\n");
    char error[512];
    size_t size = 0;
    ssx_plan *plan = ssx_plan_read(decimal, strlen(decimal), error, sizeof error);
    CHECK(plan != NULL);
    char *text = ssx_plan_write(plan, &size);
    CHECK(text != NULL && strcmp(text, expected) == 0); /* the decimal times, exactly */
    ssx_plan_text_free(text);
    ssx_plan_free(plan);

    strcat(expected, "table_column 0 real 1 ");
    hex_list(expected + strlen(expected), column, ROWS);
    strcat(expected, "\n");
    plan = ssx_plan_read(expected, strlen(expected), error, sizeof error);
    if (plan == NULL) {
        fprintf(stderr, "refused: %s\n", error);
    }
    CHECK(plan != NULL);
    text = ssx_plan_write(plan, &size);
    CHECK(text != NULL && size == strlen(expected) && strcmp(text, expected) == 0);
    ssx_plan_text_free(text);
    ssx_plan_free(plan);

    const char short_list[] = "syssimx-plan 1\nsystem \"s\"\ntable \"t\" x2:"
                              "0000000000000000000000000000f03f\n";
    plan = ssx_plan_read(short_list, sizeof short_list - 1, error, sizeof error);
    CHECK(plan != NULL);
    text = ssx_plan_write(plan, &size);
    CHECK(strcmp(text, "syssimx-plan 1\nsystem \"s\"\ntable \"t\" 2 0 1\n") == 0);
    ssx_plan_text_free(text);
    ssx_plan_free(plan);
}

/* Each text is refused with a message that holds `expected`. */
static void refusals(void)
{
    static const struct {
        const char *text;
        const char *expected;
    } cases[] = {
        {"", "line 1: a plan starts with the line 'syssimx-plan 1'"},
        {"syssimx-plan 2\n", "line 1: a plan starts"},
        {"syssimx-plan 1\n", "no 'system' record"},
        {"syssimx-plan 1\nexperiment 0 1 1\n", "line 2: the first record is 'system'"},
        {"syssimx-plan 1\nsystem \"s\"\nsystem \"t\"\n", "line 3: record 'system'"},
        {"syssimx-plan 1\nsystem \"s\"\nfrobnicate 1\n", "line 3: unknown keyword 'frobnicate'"},
        {"syssimx-plan 1\nsystem \"s\"\n\"quoted\"\n", "line 3: a record starts with its keyword"},
        {"syssimx-plan 1\nsystem s\n", "line 2: record 'system', field NAME: a string is "
                                       "written in double quotes"},
        {"syssimx-plan 1\nsystem \"s\nx\"\n", "line 2: record 'system', field NAME: the string "
                                              "has no closing quote"},
        {"syssimx-plan 1\nsystem \"a\\q\"\n", "field NAME: unknown escape \\q"},
        {"syssimx-plan 1\nsystem \"a\\x4\"\n", "field NAME: \\x needs two hex digits"},
        {"syssimx-plan 1\nsystem \"a\\x00\"\n", "field NAME: a name or path may not hold a NUL"},
        {"syssimx-plan 1\nsystem \"a\"b\n", "closing quote is not followed by a space"},
        {"syssimx-plan 1\nsystem \"s\" 1\n", "line 2: record 'system': more fields"},
        {"syssimx-plan 1\nsystem \"s\"\nexperiment 0 1\n",
         "line 3: record 'experiment', field STEP: missing"},
        {"syssimx-plan 1\nsystem \"s\"\nexperiment 0 1 x\n", "field STEP: 'x' is not a number"},
        {"syssimx-plan 1\nsystem \"s\"\nexperiment 0 1 1\nexperiment 0 1 1\n",
         "line 4: record 'experiment': a second experiment (the first on line 3)"},
        {"syssimx-plan 1\nsystem \"s\"\nthreads 1.5\n", "field N: '1.5' is not an integer"},
        {"syssimx-plan 1\nsystem \"s\"\nthreads 99999999999\n", "field N: 99999999999 is outside"},
        {"syssimx-plan 1\nsystem \"s\"\nhistory 2\n", "field KEEP: 2 is outside 0..1"},
        {"syssimx-plan 1\nsystem \"s\"\nthreads 1111111111111111111111111111111111111111111"
         "111111111111111111111111111\n", "is too long for a number"},
        {"syssimx-plan 1\nsystem \"s\"\ncoupling sideways\n",
         "field COUPLING: 'sideways' is none of gauss_seidel, jacobi"},
        {"syssimx-plan 1\nsystem \"s\"\noutput 0 real 1\n",
         "line 3: record 'output', field COMPONENT: no component 0 defined before"},
        {"syssimx-plan 1\nsystem \"s\"\npython \"p\" 0\nconnect 0 0 0 0 1 0\n",
         "line 4: record 'connect', field SRC_OUTPUT: component 0 has no output 0"},
        {"syssimx-plan 1\nsystem \"s\"\npython \"p\" 0\noutput 0 real 0\nconnect 0 0 0 0 1 0\n",
         "line 5: record 'connect', field DST_INPUT: component 0 has no input 0"},
        {"syssimx-plan 1\nsystem \"s\"\nindicator_slope 0 1\n",
         "line 3: record 'indicator_slope', field INDICATOR: no indicator 0"},
        {"syssimx-plan 1\nsystem \"s\"\nsubscribe indicator 0 0\n",
         "field LISTENER: no component 0"},
        {"syssimx-plan 1\nsystem \"s\"\npython \"p\" 0\nsubscribe indicator 0 0\n",
         "line 4: record 'subscribe', field INDEX: no indicator 0 defined before"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" 2 0 1\ntable_column 0 real 0 1 5\n",
         "line 4: record 'table_column', field VALUES: 1 values for a table of 2 rows"},
        {"syssimx-plan 1\nsystem \"s\"\npython \"p\" 0\ntable_column 0 real 0 0\n",
         "line 4: record 'table_column', field COMPONENT: component 0 is not a table"},
        {"syssimx-plan 1\nsystem \"s\"\npython \"p\" 0\nstart 0 real 1 0\n",
         "line 4: record 'start', field COMPONENT: component 0 is not an FMU"},
        {"syssimx-plan 1\nsystem \"s\"\nfmu \"a\" 1 2 \"a\" \"a\" \"g\" \"\" 0\n"
         "fmi3_variable 0 1 float64 \"x\"\n",
         "line 4: record 'fmi3_variable', field COMPONENT: component 0 is an FMI 2.0 FMU, not "
         "FMI 3.0"},
        {"syssimx-plan 1\nsystem \"s\"\nfmu \"a\" 1 4 \"a\" \"a\" \"g\" \"\" 0\n",
         "field VERSION: 4 is outside 1..3"},
        {"syssimx-plan 1\nsystem \"s\"\nfmu \"a\" 1 2 \"a\" \"a\" \"g\" \"\" 0\n"
         "start 0 real 1 \"text\"\n", "line 4: record 'start', field VALUE: a real value is a "
                                     "number"},
        {"syssimx-plan 1\nsystem \"s\"\nfmu \"a\" 1 2 \"a\" \"a\" \"g\" \"\" 0\n"
         "start 0 string 1 2\n", "field VALUE: a string value is a string"},
        {"syssimx-plan 1\nsystem \"s\"\nfmu \"a\" 1 2 \"a\" \"a\" \"g\" \"\" 0\n"
         "start 0 boolean 1 0.5\n", "field VALUE: a boolean value is 0 or 1"},
        {"syssimx-plan 1\nsystem \"s\"\nfmu \"a\" 1 2 \"a\" \"a\" \"g\" \"\" 0\n"
         "input 0 integer 1 2.5\n", "record 'input', field START: 2.5 is not an integer"},
        {"syssimx-plan 1\nsystem \"s\"\nfmu \"a\" 1 2 \"a\" \"a\" \"g\" \"\" 0\n"
         "output 0 real 0\nrestart_handler 0 0 0 0 0 0 0 0 1 1 3 1 0\n",
         "line 5: record 'restart_handler', field TERMS (item 1): component 0 has no output 3"},
        {"syssimx-plan 1\nsystem \"s\"\npython \"p\" 0\nschedule 1 2 0 0\n",
         "line 4: record 'schedule', field GROUPS (item 1): missing"},
        {"syssimx-plan 1\nsystem \"s\"\npower_bonds 99999999 0\n", "field BONDS: 99999999 is "
                                                                  "outside 0..67108864"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" x1:000000000000f03\n",
         "line 3: record 'table', field TIMES: the hex list has an odd number of digits (15)"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" x2:000000000000f03f\n",
         "line 3: record 'table', field TIMES: the hex list holds 16 digits for 2 values (16 a "
         "value)"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" x1:0000000000000000ff\n",
         "field TIMES: the hex list holds 18 digits"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" x2:000000000000f03f000000000000F03F\n",
         "line 3: record 'table', field TIMES (item 2): 'F' is not a lowercase hex digit"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" x1:00000000000g003f\n",
         "field TIMES (item 1): 'g' is not a lowercase hex digit"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" x1\n",
         "field TIMES: a hex list is x, its count, ':' and its digits; 'x1' has no ':'"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" x99999999:\n",
         "field TIMES: 99999999 is outside 0..67108864"},
        {"syssimx-plan 1\nsystem \"s\"\ntable \"t\" 1 0\ntable_column 0 real 0 x2:"
         "00000000000000000000000000000000\n",
         "line 4: record 'table_column', field VALUES: 2 values for a table of 1 rows"},
        {"syssimx-plan 1\nsystem \"s\"\npower_bonds x0:\n",
         "field BONDS: 'x0:' is not an integer"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        char error[512] = "untouched";
        ssx_plan *plan = ssx_plan_read(cases[k].text, strlen(cases[k].text), error,
                                       sizeof error);
        if (plan != NULL || strstr(error, cases[k].expected) == NULL) {
            fprintf(stderr, "case %zu: error \"%s\" lacks \"%s\"\n", k, error, cases[k].expected);
            exit(1);
        }
    }
    /* a NUL byte is part of the text it stands in */
    const char nul[] = "syssimx-plan 1\nsystem \"s\"\nthreads\0 1\n";
    char error[512];
    CHECK(ssx_plan_read(nul, sizeof nul - 1, error, sizeof error) == NULL);
    CHECK(strstr(error, "line 3: unknown keyword") != NULL);
}

/* One of the built FMUs laid out as an unpacked archive, its binary under
 * binaries/<platform>/<stem>.so and its modelDescription.xml (links), in a new temporary
 * folder (written into base). Its guid or instantiation token into *token when token is not
 * NULL. */
static const struct {
    const char *stem, *binary, *guid;
} built_fmus[] = {ENGINE_TEST_FMUS};

static void unpacked(const char *stem, const char *platform, char *base, size_t size,
                     const char **token)
{
    const char *binary = NULL;
    for (size_t k = 0; k < sizeof built_fmus / sizeof built_fmus[0]; ++k) {
        if (strcmp(built_fmus[k].stem, stem) == 0) {
            binary = built_fmus[k].binary;
            if (token != NULL) {
                *token = built_fmus[k].guid;
            }
        }
    }
    CHECK(binary != NULL);
    const char *tmp = getenv("TMPDIR");
    snprintf(base, size, "%s/ssx_plan_XXXXXX", tmp != NULL ? tmp : "/tmp");
    CHECK(mkdtemp(base) != NULL);
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", base, stem);
    CHECK(mkdir(path, 0700) == 0);
    snprintf(path, sizeof path, "%s/%s/binaries", base, stem);
    CHECK(mkdir(path, 0700) == 0);
    snprintf(path, sizeof path, "%s/%s/binaries/%s", base, stem, platform);
    CHECK(mkdir(path, 0700) == 0);
    snprintf(path, sizeof path, "%s/%s/binaries/%s/%s.so", base, stem, platform, stem);
    CHECK(symlink(binary, path) == 0);
    /* the build writes it beside the binary, as <stem>_modelDescription.xml */
    char description[1024];
    snprintf(description, sizeof description, "%.*s_modelDescription.xml",
             (int)(strlen(binary) - 3), binary);
    snprintf(path, sizeof path, "%s/%s/modelDescription.xml", base, stem);
    CHECK(symlink(description, path) == 0);
}

static void remove_unpacked(const char *base, const char *stem, const char *platform)
{
    char paths[6][1024];
    snprintf(paths[0], sizeof paths[0], "%s/%s/binaries/%s/%s.so", base, stem, platform, stem);
    snprintf(paths[1], sizeof paths[1], "%s/%s/binaries/%s", base, stem, platform);
    snprintf(paths[2], sizeof paths[2], "%s/%s/binaries", base, stem);
    snprintf(paths[3], sizeof paths[3], "%s/%s/modelDescription.xml", base, stem);
    snprintf(paths[4], sizeof paths[4], "%s/%s", base, stem);
    snprintf(paths[5], sizeof paths[5], "%s", base);
    for (size_t k = 0; k < 6; ++k) {
        CHECK(remove(paths[k]) == 0);
    }
}

static void unpacked_pendulum(char *base, size_t size)
{
    unpacked("pendulum_cvode", "linux64", base, size, NULL);
}

/* examples/pendulum_wall.yaml as Python builds it: theta0 0.5 (CVODE rtol 1e-10), an
 * indicator on theta falling, the declarative restart with omega reversed. */
static const char seed_plan[] =
    "syssimx-plan 1\n"
    "system \"pendulum against a wall\"\n"
    "experiment 0 1 0.05\n"
    "fmu \"P\" 1 2 \"pendulum_cvode\" \"pendulum_cvode\" \"{e4eeb2ef-23e1-5e9f-4db4-f873308f2419}\" "
    "\"P\" 0\n"
    "fmu_experiment 0 0 0 0 0\n"
    "start 0 real 7 0.5\n"
    "start 0 real 8 0\n"
    "start 0 real 11 1e-10\n"
    "output 0 real 0\n"
    "output 0 real 1\n"
    "output 0 real 2\n"
    "input 0 real 4 nan\n"
    "directional_derivatives 0 1\n"
    "interpolation 0 1 1\n"
    "indicator_output 0 0 -1\n"
    "indicator_slope 0 3\n"
    "subscribe indicator 0 0\n"
    "restart_handler 0 0 0 0 0 1 11 1e-10 0 0 2 7 0 1 0 8 1 -1 0\n"
    "hybrid_options 1e-09 1e-09 100 10 0 illinois 0\n";

static void standalone_seed(void)
{
    char base[512];
    unpacked_pendulum(base, sizeof base);
    char error[1024];
    ssx_plan *plan = ssx_plan_read(seed_plan, sizeof seed_plan - 1, error, sizeof error);
    CHECK(plan != NULL);
    ssx_system *sys = ssx_plan_build(plan, base, NULL, 0, error, sizeof error);
    if (sys == NULL) {
        fprintf(stderr, "build: %s\n", error);
    }
    CHECK(sys != NULL);
    double t0, tf, dt;
    CHECK(ssx_plan_experiment(plan, &t0, &tf, &dt) == 0);
    CHECK_OK(sys, ssx_plan_initialize(sys, plan, t0));
    CHECK_OK(sys, ssx_run(sys, t0, tf, dt));
    CHECK(ssx_event_count(sys) >= 1);
    ssx_event_record event;
    CHECK(ssx_event_get(sys, 0, &event) == 0);
    CHECK_CLOSE(event.t, PENDULUM_QUARTER_PERIOD, 1e-9);
    printf("standalone seed: wall hit at %.17g s, %zu events, %zu samples\n", event.t,
           ssx_event_count(sys), ssx_history_length(sys));
    ssx_system_free(sys); /* frees the FMU the build loaded */

    /* a missing folder and a plan that is not the system's are refused, naming them */
    sys = ssx_plan_build(plan, "/nonexistent-folder", NULL, 0, error, sizeof error);
    CHECK(sys == NULL && strstr(error, "line 4: record 'fmu': component 0: its folder "
                                       "'/nonexistent-folder/pendulum_cvode' is not there"));
    ssx_plan_free(plan);
    remove_unpacked(base, "pendulum_cvode", "linux64");
}

/* The FMI 3.0 bouncing ball's plan, its type table given by records or (types 0) read from
 * its modelDescription.xml by the builder. */
static ssx_plan *ball_plan(const char *token, int types)
{
    char text[2048];
    snprintf(text, sizeof text,
             "syssimx-plan 1\n"
             "system \"ball\"\n"
             "model_exchange \"Ball\" 1 2 1 3 \"bouncing_ball_cvode_fmi3\" "
             "\"bouncing_ball_cvode_fmi3\" \"%s\" \"Ball\" 0\n"
             "fmu_experiment 0 1 1e-12 0 0\n"
             "start 0 real 5 0.8\n"
             "start 0 real 8 1e-06\n"
             "%s"
             "output 0 real 0\n"
             "output 0 real 1\n",
             token,
             types ? "fmi3_variables 0 0 0\n"
                     "fmi3_variable 0 0 float64 \"h\"\n"
                     "fmi3_variable 0 1 float64 \"v\"\n"
                     "fmi3_variable 0 5 float64 \"e\"\n"
                     "fmi3_variable 0 8 float64 \"gap_tol\"\n"
                   : "");
    char error[1024];
    ssx_plan *plan = ssx_plan_read(text, strlen(text), error, sizeof error);
    CHECK(plan != NULL);
    return plan;
}

/* An FMI 3.0 Model Exchange FMU built from a plan, its type table from the plan's fmi3_*
 * records and then from its modelDescription.xml: the bouncing ball's bounces are its own
 * state events at the closed form either way. Without records or a modelDescription.xml the
 * build is refused, naming the file. */
static void standalone_fmi3_model_exchange(void)
{
    char base[512];
    const char *token = NULL;
    unpacked("bouncing_ball_cvode_fmi3", "x86_64-linux", base, sizeof base, &token);
    char error[1024];
    for (int types = 1; types >= 0; --types) {
        ssx_plan *plan = ball_plan(token, types);
        ssx_system *sys = ssx_plan_build(plan, base, NULL, 0, error, sizeof error);
        if (sys == NULL) {
            fprintf(stderr, "build: %s\n", error);
        }
        CHECK(sys != NULL);
        CHECK_OK(sys, ssx_plan_initialize(sys, plan, 0.0));
        check_own_bounces(sys);
        ssx_system_free(sys);
        ssx_plan_free(plan);
    }
    char description[1024];
    snprintf(description, sizeof description, "%s/bouncing_ball_cvode_fmi3/modelDescription.xml",
             base);
    CHECK(remove(description) == 0);
    ssx_plan *plan = ball_plan(token, 0);
    CHECK(ssx_plan_build(plan, base, NULL, 0, error, sizeof error) == NULL);
    CHECK(strstr(error, "line 3: record 'model_exchange': component 0: cannot read ") == error);
    CHECK(strstr(error, "modelDescription.xml (an FMI 3.0 FMU without fmi3_variable records "
                        "needs it)") != NULL);
    ssx_plan_free(plan);
    CHECK(symlink("/nonexistent", description) == 0); /* for remove_unpacked */
    remove_unpacked(base, "bouncing_ball_cvode_fmi3", "x86_64-linux");
}

/* A given FMU is borrowed: the build loads nothing, the caller initializes it. */
static void given_fmu(void)
{
    char error[1024];
    ssx_plan *plan = ssx_plan_read(seed_plan, sizeof seed_plan - 1, error, sizeof error);
    CHECK(plan != NULL);
    ssx_fmu *fmu = load_fmu("pendulum_cvode");
    ssx_fmu *given[] = {fmu};
    ssx_system *sys = ssx_plan_build(plan, "/nonexistent-folder", given, 1, error, sizeof error);
    CHECK(sys != NULL);
    CHECK(start_pendulum(fmu, 0.0, 0.5, 0.0, 0.0) == 0);
    CHECK_OK(sys, ssx_initialize(sys, 0.0));
    CHECK_OK(sys, ssx_run(sys, 0.0, 0.6, 0.05));
    ssx_event_record event;
    CHECK(ssx_event_count(sys) == 1 && ssx_event_get(sys, 0, &event) == 0);
    CHECK_CLOSE(event.t, PENDULUM_QUARTER_PERIOD, 1e-6);
    ssx_system_free(sys);
    ssx_fmu_free(fmu); /* still the caller's */
    ssx_plan_free(plan);
}

/* Refusals of the build and of the initialization name the record's line and the reason. */
static void build_refusals(void)
{
    char error[1024];
    const char twice[] = "syssimx-plan 1\nsystem \"s\"\npython \"p\" 0\noutput 0 real 0\n"
                         "input 0 real 0 0\nconnect 0 0 0 0 1 0\nconnect 0 0 0 0 1 0\n";
    ssx_plan *plan = ssx_plan_read(twice, sizeof twice - 1, error, sizeof error);
    CHECK(plan != NULL);
    CHECK(ssx_plan_build(plan, NULL, NULL, 0, error, sizeof error) == NULL);
    CHECK(strncmp(error, "line 7: record 'connect': ", 26) == 0 && strlen(error) > 30);
    ssx_plan_free(plan);

    char base[512];
    unpacked_pendulum(base, sizeof base);
    const char isolated[] = "syssimx-plan 1\nsystem \"s\"\n"
                            "fmu \"P\" 1 2 \"pendulum_cvode\" \"pendulum_cvode\" \"g\" \"\" 0\n"
                            "isolated 0 1\n";
    plan = ssx_plan_read(isolated, sizeof isolated - 1, error, sizeof error);
    CHECK(plan != NULL);
    CHECK(ssx_plan_build(plan, base, NULL, 0, error, sizeof error) == NULL);
    CHECK(strstr(error, "line 4: record 'isolated': component 0 runs in a host process"));
    ssx_plan_free(plan);

    const char no_binary[] = "syssimx-plan 1\nsystem \"s\"\n"
                             "fmu \"P\" 1 2 \"pendulum_cvode\" \"other_model\" \"g\" \"\" 0\n";
    plan = ssx_plan_read(no_binary, sizeof no_binary - 1, error, sizeof error);
    CHECK(plan != NULL);
    CHECK(ssx_plan_build(plan, base, NULL, 0, error, sizeof error) == NULL);
    CHECK(strstr(error, "line 3: record 'fmu': component 0: ") == error);
    ssx_plan_free(plan);

    /* a start value the FMU refuses fails the initialization, naming the component */
    char refused[sizeof seed_plan + 32];
    snprintf(refused, sizeof refused, "%sstart 0 real 999 1\n", seed_plan);
    plan = ssx_plan_read(refused, strlen(refused), error, sizeof error);
    CHECK(plan != NULL);
    ssx_system *sys = ssx_plan_build(plan, base, NULL, 0, error, sizeof error);
    CHECK(sys != NULL);
    CHECK(ssx_plan_initialize(sys, plan, 0.0) == -1);
    CHECK(ssx_last_error(sys)->kind == SSX_ERROR_FMI && ssx_last_error(sys)->component == 0);
    /* and a plan that did not build the system is refused */
    ssx_plan *other = ssx_plan_read(twice, sizeof twice - 1, error, sizeof error);
    CHECK(ssx_plan_initialize(sys, other, 0.0) == -1);
    CHECK_MESSAGE(sys, "not built from this plan");
    ssx_plan_free(other);
    ssx_system_free(sys);
    ssx_plan_free(plan);
    remove_unpacked(base, "pendulum_cvode", "linux64");
}

int main(void)
{
    round_trip();
    hex_round_trip();
    refusals();
    standalone_seed();
    standalone_fmi3_model_exchange();
    given_fmu();
    build_refusals();
    return 0;
}
