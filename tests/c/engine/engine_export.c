/* The exported FMU's binary (src/export/) driven as an importer drives it, through its FMI 2.0
 * and 3.0 entry points: the seed's pendulum against a wall laid out as an export's resources
 * (the plan, the export map, the member unpacked under members/). The wall hit located inside
 * doStep at the quarter period, the FMU state saved, serialized and restored, a reset and a
 * second run, a wrong token refused with its reason logged; FMI 3.0 returns early at the hit.
 * Run under AddressSanitizer too: every allocation of the binary is freed. */
#define _XOPEN_SOURCE 700 /* mkdtemp, symlink */
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "engine_test_fmus.h"
#include "fmi2Functions.h"
#include "fmi3Functions.h"
#include "test_support.h"

static const double quarter_period = 0.46507759431173046;
static const double step = 0.05;
static const char token[] = "{export-test}";
enum { VR_TORQUE = 1, VR_THETA, VR_OMEGA, VR_EVENTS, VR_LAST_EVENT_TIME };

static const char export_map[] = "syssimx-export 1\n"
                                 "token \"{export-test}\"\n"
                                 "step 0.05\n"
                                 "variable 1 input 0 0 real 0.0 P.torque\n"
                                 "variable 2 output 0 0 real nan P.theta\n"
                                 "variable 3 output 0 1 real nan P.omega\n"
                                 "variable 4 events -1 -1 integer nan events\n"
                                 "variable 5 last_event_time -1 -1 real nan last_event_time\n";

/* examples/pendulum_wall.yaml as Python writes its plan (%s: the member's guid) */
static const char seed_plan[] =
    "syssimx-plan 1\n"
    "system \"pendulum against a wall\"\n"
    "fmu \"P\" 1 2 \"pendulum_cvode\" \"pendulum_cvode\" \"%s\" \"P\" 0\n"
    "fmu_experiment 0 0 0 0 0\n"
    "start 0 real 7 0.5\n"
    "start 0 real 8 0\n"
    "start 0 real 11 1e-10\n"
    "output 0 real 0\n"
    "output 0 real 1\n"
    "input 0 real 4 nan\n"
    "indicator_output 0 0 -1\n"
    "indicator_slope 0 3\n"
    "subscribe indicator 0 0\n"
    "restart_handler 0 0 0 0 0 1 11 1e-10 0 0 2 7 0 1 0 8 1 -1 0\n"
    "hybrid_options 1e-09 1e-09 100 10 0 illinois 0\n";

static const struct {
    const char *stem, *binary, *guid;
} built_fmus[] = {ENGINE_TEST_FMUS};

/* base/resources/{system.plan, export.map, members/pendulum_cvode/...} in a new folder; the
 * paths made, to remove them in reverse */
typedef struct {
    const char *base;
    char paths[9][1024];
    size_t n_paths;
} layout;

static const char *path_in(layout *l, const char *relative)
{
    CHECK(l->n_paths < sizeof l->paths / sizeof l->paths[0]);
    snprintf(l->paths[l->n_paths], sizeof l->paths[l->n_paths], "%s/%s", l->base, relative);
    return l->paths[l->n_paths++];
}

static void write_file(const char *path, const char *text)
{
    FILE *file = fopen(path, "w");
    CHECK(file != NULL && fputs(text, file) >= 0 && fclose(file) == 0);
}

static void lay_out(layout *l, char *base, size_t size)
{
    const char *binary = NULL, *guid = NULL;
    for (size_t k = 0; k < sizeof built_fmus / sizeof built_fmus[0]; ++k) {
        if (strcmp(built_fmus[k].stem, "pendulum_cvode") == 0) {
            binary = built_fmus[k].binary;
            guid = built_fmus[k].guid;
        }
    }
    CHECK(binary != NULL);
    const char *tmp = getenv("TMPDIR");
    snprintf(base, size, "%s/ssx_export_XXXXXX", tmp != NULL ? tmp : "/tmp");
    CHECK(mkdtemp(base) != NULL);
    l->base = base;
    const char *folders[] = {"resources", "resources/members", "resources/members/pendulum_cvode",
                             "resources/members/pendulum_cvode/binaries",
                             "resources/members/pendulum_cvode/binaries/linux64"};
    for (size_t k = 0; k < sizeof folders / sizeof folders[0]; ++k) {
        CHECK(mkdir(path_in(l, folders[k]), 0700) == 0);
    }
    CHECK(symlink(binary, path_in(l, "resources/members/pendulum_cvode/binaries/linux64/"
                                     "pendulum_cvode.so")) == 0);
    char plan[2048];
    snprintf(plan, sizeof plan, seed_plan, guid);
    write_file(path_in(l, "resources/system.plan"), plan);
    write_file(path_in(l, "resources/export.map"), export_map);
}

static void remove_layout(layout *l)
{
    for (size_t k = l->n_paths; k-- > 0;) {
        CHECK(remove(l->paths[k]) == 0);
    }
    CHECK(remove(l->base) == 0);
}

/* the loggers keep the last message in the buffer the instance's environment points to */
enum { LOGGED_SIZE = 4096 };

static void log_fmi2(fmi2ComponentEnvironment environment, fmi2String instance, fmi2Status status,
                     fmi2String category, fmi2String message, ...)
{
    (void)instance, (void)status, (void)category;
    va_list arguments;
    va_start(arguments, message);
    vsnprintf(environment, LOGGED_SIZE, message, arguments);
    va_end(arguments);
}

static void log_fmi3(fmi3InstanceEnvironment environment, fmi3Status status, fmi3String category,
                     fmi3String message)
{
    (void)status, (void)category;
    snprintf(environment, LOGGED_SIZE, "%s", message);
}

#define LOOKUP(library, name) name##TYPE *name = (name##TYPE *)dlsym(library, #name)

/* Steps from t to 1 s; the outputs there. */
static void fmi2_to_the_end(void *library, fmi2Component c, double t, double values[2], int *events)
{
    LOOKUP(library, fmi2DoStep);
    LOOKUP(library, fmi2GetReal);
    LOOKUP(library, fmi2GetInteger);
    for (; t < 1.0 - step / 2; t += step) {
        CHECK(fmi2DoStep(c, t, step, fmi2True) == fmi2OK);
    }
    const fmi2ValueReference outputs[] = {VR_THETA, VR_OMEGA}, count = VR_EVENTS;
    CHECK(fmi2GetReal(c, outputs, 2, values) == fmi2OK);
    CHECK(fmi2GetInteger(c, &count, 1, events) == fmi2OK);
}

static void fmi2_run(void *library, const char *resources)
{
    LOOKUP(library, fmi2Instantiate);
    LOOKUP(library, fmi2SetupExperiment);
    LOOKUP(library, fmi2EnterInitializationMode);
    LOOKUP(library, fmi2ExitInitializationMode);
    LOOKUP(library, fmi2DoStep);
    LOOKUP(library, fmi2GetReal);
    LOOKUP(library, fmi2GetFMUstate);
    LOOKUP(library, fmi2SetFMUstate);
    LOOKUP(library, fmi2FreeFMUstate);
    LOOKUP(library, fmi2SerializedFMUstateSize);
    LOOKUP(library, fmi2SerializeFMUstate);
    LOOKUP(library, fmi2DeSerializeFMUstate);
    LOOKUP(library, fmi2Reset);
    LOOKUP(library, fmi2Terminate);
    LOOKUP(library, fmi2FreeInstance);
    CHECK(fmi2FreeInstance != NULL && fmi2DeSerializeFMUstate != NULL);
    char logged[LOGGED_SIZE] = "";
    fmi2CallbackFunctions callbacks = {log_fmi2, calloc, free, NULL, logged};

    CHECK(fmi2Instantiate("wall", fmi2CoSimulation, "{another}", resources, &callbacks, fmi2False,
                          fmi2False) == NULL);
    CHECK(strstr(logged, "is not this FMU's {export-test}") != NULL);

    fmi2Component c = fmi2Instantiate("wall", fmi2CoSimulation, token, resources, &callbacks,
                                      fmi2False, fmi2False);
    CHECK(c != NULL);
    for (int round = 0; round < 2; ++round) { /* the second after fmi2Reset */
        CHECK(fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK);
        CHECK(fmi2EnterInitializationMode(c) == fmi2OK);
        CHECK(fmi2ExitInitializationMode(c) == fmi2OK);
        double t = 0.0;
        for (int k = 0; k < 8; ++k, t += step) {
            CHECK(fmi2DoStep(c, t, step, fmi2True) == fmi2OK);
        }
        fmi2FMUstate at_0_4 = NULL;
        CHECK(fmi2GetFMUstate(c, &at_0_4) == fmi2OK);
        size_t size = 0;
        CHECK(fmi2SerializedFMUstateSize(c, at_0_4, &size) == fmi2OK && size > 0);
        fmi2Byte *bytes = malloc(size);
        CHECK(bytes != NULL && fmi2SerializeFMUstate(c, at_0_4, bytes, size) == fmi2OK);
        double first[2], restored[2], deserialized[2];
        int events = -1;
        fmi2_to_the_end(library, c, t, first, &events);
        CHECK(events == 1);
        const fmi2ValueReference last = VR_LAST_EVENT_TIME;
        double hit;
        CHECK(fmi2GetReal(c, &last, 1, &hit) == fmi2OK);
        CHECK_CLOSE(hit, quarter_period, 1e-9);
        CHECK(first[0] > 0.0);

        CHECK(fmi2SetFMUstate(c, at_0_4) == fmi2OK);
        fmi2_to_the_end(library, c, t, restored, &events);
        CHECK(events == 1);
        CHECK_CLOSE(restored[0], first[0], 1e-8); /* the member restarts CVODE when restored */
        fmi2FMUstate copy = NULL;
        CHECK(fmi2DeSerializeFMUstate(c, bytes, size, &copy) == fmi2OK);
        CHECK(fmi2SetFMUstate(c, copy) == fmi2OK);
        fmi2_to_the_end(library, c, t, deserialized, &events);
        CHECK(deserialized[0] == restored[0] && deserialized[1] == restored[1]);
        /* bytes of another length are no state of this FMU */
        fmi2FMUstate none = NULL;
        CHECK(fmi2DeSerializeFMUstate(c, bytes, 4, &none) == fmi2Error && none == NULL);
        free(bytes);
        CHECK(fmi2FreeFMUstate(c, &at_0_4) == fmi2OK && fmi2FreeFMUstate(c, &copy) == fmi2OK);
        CHECK(fmi2Terminate(c) == fmi2OK);
        CHECK(fmi2Reset(c) == fmi2OK);
    }
    fmi2FreeInstance(c);
}

static void fmi3_run(void *library, const char *resource_path)
{
    LOOKUP(library, fmi3InstantiateCoSimulation);
    LOOKUP(library, fmi3EnterInitializationMode);
    LOOKUP(library, fmi3ExitInitializationMode);
    LOOKUP(library, fmi3UpdateDiscreteStates);
    LOOKUP(library, fmi3EnterStepMode);
    LOOKUP(library, fmi3DoStep);
    LOOKUP(library, fmi3GetFloat64);
    LOOKUP(library, fmi3GetInt32);
    LOOKUP(library, fmi3GetFloat32);
    LOOKUP(library, fmi3Terminate);
    LOOKUP(library, fmi3FreeInstance);
    CHECK(fmi3FreeInstance != NULL && fmi3GetFloat32 != NULL);
    char logged[LOGGED_SIZE] = "";
    fmi3Instance c =
        fmi3InstantiateCoSimulation("wall", token, resource_path, fmi3False, fmi3False, fmi3True,
                                    fmi3True, NULL, 0, logged, log_fmi3, NULL);
    CHECK(c != NULL);
    CHECK(fmi3EnterInitializationMode(c, fmi3False, 0.0, 0.0, fmi3False, 0.0) == fmi3OK);
    CHECK(fmi3ExitInitializationMode(c) == fmi3OK); /* into event mode: eventModeUsed */
    fmi3Boolean flags[4], terminate;
    fmi3Float64 next;
    CHECK(fmi3UpdateDiscreteStates(c, &flags[0], &terminate, &flags[1], &flags[2], &flags[3],
                                   &next) == fmi3OK);
    CHECK(!flags[0] && !terminate);
    CHECK(fmi3EnterStepMode(c) == fmi3OK);
    double t = 0.0, early_at = -1.0;
    int calls = 0;
    while (t < 1.0 - 1e-12) {
        double grid_point = step * floor(t / step + 1.0 + 1e-9);
        fmi3Boolean handling, early;
        fmi3Float64 reached;
        CHECK(fmi3DoStep(c, t, grid_point - t, fmi3True, &handling, &terminate, &early, &reached) ==
              fmi3OK);
        CHECK(!handling && !terminate);
        if (early) {
            early_at = reached;
        }
        t = reached;
        ++calls;
    }
    CHECK_CLOSE(early_at, quarter_period, 1e-9);
    CHECK(calls == 21); /* the grid's 20 steps and the rest of the step cut at the hit */
    const fmi3ValueReference count = VR_EVENTS, last = VR_LAST_EVENT_TIME;
    fmi3Int32 events = -1;
    fmi3Float64 hit = -1.0;
    CHECK(fmi3GetInt32(c, &count, 1, &events, 1) == fmi3OK && events == 1);
    CHECK(fmi3GetFloat64(c, &last, 1, &hit, 1) == fmi3OK && hit == early_at);
    /* a type this FMU has no variable of is declined with its reason */
    fmi3Float32 value;
    CHECK(fmi3GetFloat32(c, &last, 1, &value, 1) == fmi3Error);
    CHECK(strstr(logged, "fmi3GetFloat32") != NULL);
    CHECK(fmi3Terminate(c) == fmi3OK);
    fmi3FreeInstance(c);
}

int main(int argc, char **argv)
{
    CHECK(argc == 2);
    void *library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    CHECK(library != NULL);
    layout l = {.n_paths = 0};
    char base[512];
    lay_out(&l, base, sizeof base);
    char uri[1024], resource_path[1024];
    snprintf(uri, sizeof uri, "file://%s/resources", l.base);
    snprintf(resource_path, sizeof resource_path, "%s/resources/", l.base);
    fmi2_run(library, uri);
    fmi3_run(library, resource_path);
    CHECK(dlclose(library) == 0);
    remove_layout(&l);
    printf("exported binary: wall hit located inside doStep (FMI 2.0 and 3.0), state and reset "
           "as an importer uses them\n");
    return 0;
}
