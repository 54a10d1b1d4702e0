/* An FMI 3.0 bouncing ball build driven from C (so AddressSanitizer sees the whole lifecycle):
 * event mode with early return at each bounce, the update in Event Mode, a state taken at an
 * early return serialized and restored with its event pending, and a refused wrong-state call.
 * Usage: test_fmi3_events <binary.so> <modelDescription.xml> */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3FunctionTypes.h"
#include "fmu_harness.h"

#define CHECK_OK3(call) CHECK((call) == fmi3OK)

typedef struct {
    fmi3InstantiateCoSimulationTYPE *instantiate;
    fmi3FreeInstanceTYPE *free_instance;
    fmi3EnterInitializationModeTYPE *enter_initialization_mode;
    fmi3ExitInitializationModeTYPE *exit_initialization_mode;
    fmi3EnterEventModeTYPE *enter_event_mode;
    fmi3UpdateDiscreteStatesTYPE *update_discrete_states;
    fmi3EnterStepModeTYPE *enter_step_mode;
    fmi3DoStepTYPE *do_step;
    fmi3GetFloat64TYPE *get_float64;
    fmi3GetFMUStateTYPE *get_state;
    fmi3SetFMUStateTYPE *set_state;
    fmi3FreeFMUStateTYPE *free_state;
    fmi3SerializedFMUStateSizeTYPE *serialized_size;
    fmi3SerializeFMUStateTYPE *serialize;
    fmi3DeserializeFMUStateTYPE *deserialize;
    fmi3TerminateTYPE *terminate;
} fmi3_api;

static char last_message[1024];

static void record(fmi3InstanceEnvironment environment, fmi3Status status, fmi3String category,
                   fmi3String message)
{
    (void)environment, (void)status, (void)category;
    snprintf(last_message, sizeof last_message, "%s", message);
}

static void *resolve(void *library, const char *name)
{
    void *symbol = dlsym(library, name);
    if (symbol == NULL) {
        fprintf(stderr, "the binary does not export %s\n", name);
        exit(1);
    }
    return symbol;
}

/* The attribute value after `key` in the description text (the test fails without one). */
static void attribute_after(const char *text, const char *key, char *value, size_t size)
{
    const char *found = strstr(text, key);
    CHECK(found != NULL);
    found += strlen(key);
    size_t length = strcspn(found, "\"");
    CHECK(length < size);
    memcpy(value, found, length);
    value[length] = '\0';
}

static double get(const fmi3_api *api, fmi3Instance c, fmi3ValueReference vr)
{
    double value = NAN;
    CHECK_OK3(api->get_float64(c, &vr, 1, &value, 1));
    return value;
}

/* One discrete update in Event Mode, then back to Step Mode; whether the states changed. */
static int update_and_step_on(const fmi3_api *api, fmi3Instance c)
{
    fmi3Boolean need_update, terminate, nominals, values, time_defined;
    fmi3Float64 next_time;
    CHECK_OK3(api->update_discrete_states(c, &need_update, &terminate, &nominals, &values,
                                          &time_defined, &next_time));
    CHECK(!need_update && !terminate && !nominals && !time_defined);
    CHECK_OK3(api->enter_step_mode(c));
    return values;
}

/* Applies the pending bounce in Event Mode; returns to Step Mode. */
static void handle_event(const fmi3_api *api, fmi3Instance c)
{
    CHECK_OK3(api->enter_event_mode(c));
    CHECK(update_and_step_on(api, c));
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s <binary.so> <modelDescription.xml>\n", argv[0]);
        return 2;
    }
    void *library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    CHECK(library != NULL);
    fmi3_api api;
    void *symbol;
#define RESOLVE(field, name)                      \
    symbol = resolve(library, name);              \
    memcpy(&api.field, &symbol, sizeof api.field)
    RESOLVE(instantiate, "fmi3InstantiateCoSimulation");
    RESOLVE(free_instance, "fmi3FreeInstance");
    RESOLVE(enter_initialization_mode, "fmi3EnterInitializationMode");
    RESOLVE(exit_initialization_mode, "fmi3ExitInitializationMode");
    RESOLVE(enter_event_mode, "fmi3EnterEventMode");
    RESOLVE(update_discrete_states, "fmi3UpdateDiscreteStates");
    RESOLVE(enter_step_mode, "fmi3EnterStepMode");
    RESOLVE(do_step, "fmi3DoStep");
    RESOLVE(get_float64, "fmi3GetFloat64");
    RESOLVE(get_state, "fmi3GetFMUState");
    RESOLVE(set_state, "fmi3SetFMUState");
    RESOLVE(free_state, "fmi3FreeFMUState");
    RESOLVE(serialized_size, "fmi3SerializedFMUStateSize");
    RESOLVE(serialize, "fmi3SerializeFMUState");
    RESOLVE(deserialize, "fmi3DeserializeFMUState");
    RESOLVE(terminate, "fmi3Terminate");

    FILE *file = fopen(argv[2], "rb");
    CHECK(file != NULL);
    static char description[1 << 16];
    size_t length = fread(description, 1, sizeof description - 1, file);
    fclose(file);
    description[length] = '\0';
    char token[64], text[32];
    attribute_after(description, "instantiationToken=\"", token, sizeof token);
    attribute_after(description, "name=\"v\" valueReference=\"", text, sizeof text);
    fmi3ValueReference vr_v = (fmi3ValueReference)strtoul(text, NULL, 10);

    fmi3Instance c = api.instantiate("ball", token, NULL, fmi3False, fmi3True, fmi3True, fmi3True,
                                     NULL, 0, NULL, record, NULL);
    CHECK(c != NULL);
    CHECK_OK3(api.enter_initialization_mode(c, fmi3True, 1e-10, 0.0, fmi3False, 0.0));
    CHECK_OK3(api.exit_initialization_mode(c));
    CHECK(!update_and_step_on(&api, c)); /* Event Mode after initialization: nothing pending */

    const double dt = 0.01, e = 0.8;
    double t = 0.0;
    int events = 0, k = 0;
    fmi3FMUState pending = NULL;
    while (k * dt < 3.0 - 1e-12) {
        double grid_point = k * dt + dt;
        fmi3Boolean needed, terminate, early;
        fmi3Float64 t_last;
        CHECK_OK3(api.do_step(c, t, grid_point - t, fmi3True, &needed, &terminate, &early,
                              &t_last));
        CHECK(!terminate && early == (t_last < grid_point));
        t = t_last;
        k += !early;
        if (!needed)
            continue;
        ++events;
        double before = get(&api, c, vr_v);
        if (pending == NULL) { /* the first bounce: its state also goes through bytes */
            CHECK_OK3(api.get_state(c, &pending));
            CHECK(api.do_step(c, t, dt, fmi3True, &needed, &terminate, &early, &t_last) ==
                  fmi3Error);
            CHECK(strstr(last_message, "is not handled yet") != NULL);
        }
        handle_event(&api, c);
        CHECK_NEAR("v after the bounce", get(&api, c, vr_v), -e * before, 1e-15);
    }
    CHECK(events == 6);

    size_t size = 0;
    CHECK_OK3(api.serialized_size(c, pending, &size));
    fmi3Byte *bytes = malloc(size);
    CHECK(bytes != NULL);
    CHECK_OK3(api.serialize(c, pending, bytes, size));
    fmi3FMUState copy = NULL;
    CHECK_OK3(api.deserialize(c, bytes, size, &copy));
    free(bytes);
    CHECK_OK3(api.set_state(c, copy));
    double before = get(&api, c, vr_v);
    handle_event(&api, c); /* the restored state still has its bounce to apply */
    CHECK_NEAR("v after the restored bounce", get(&api, c, vr_v), -e * before, 1e-15);
    CHECK_OK3(api.free_state(c, &copy));
    CHECK_OK3(api.free_state(c, &pending));

    CHECK_OK3(api.terminate(c));
    CHECK(api.enter_step_mode(c) == fmi3Error);
    CHECK(strcmp(last_message, "fmi3EnterStepMode is not allowed in Terminated") == 0);
    api.free_instance(c);
    dlclose(library);
    printf("%d bounces returned early and applied in Event Mode\n", events);
    return 0;
}
