/* The FMI 3.0 instance, Co-Simulation or Model Exchange: the framework's instance plus what
 * FMI 3.0 adds (its logging callback, event mode and early return), its state machine and its
 * extra variables. */
#ifndef SYSSIMX_FMI3_INSTANCE_H
#define SYSSIMX_FMI3_INSTANCE_H

#include "fmi3Functions.h"
#include "fmu_instance.h"

/* The most input clocks a model may declare (the describe tool refuses more). */
#define FMI3_MAX_CLOCKS 4

typedef struct {
    fmu_instance core; /* first: the framework works on &core */
    fmi3InstanceEnvironment environment; /* what the intermediate update receives first */
    int event_mode_used;
    int early_return_allowed;
    int model_exchange; /* made by fmi3InstantiateModelExchange */
    fmi3IntermediateUpdateCallback intermediate_update; /* NULL: the importer asked for none */
    int clock_active[FMI3_MAX_CLOCKS]; /* set by fmi3SetClock, cleared when the tick is applied */
} fmi3_instance;

/* The variables an importer may set in Intermediate Update Mode (intermediateUpdate="true"):
 * the continuous Float64 inputs. */
static inline int fmi3_intermediate_input(const model_variable *v)
{
    return v->type == TYPE_REAL && v->causality == CAUSALITY_INPUT &&
           v->variability == VARIABILITY_CONTINUOUS;
}

/* The FMI 3.0 states this FMU goes through. Co-Simulation's Event Mode is step mode of the
 * framework with in_event_mode set; Model Exchange's is the framework's event phase, and
 * Continuous-Time Mode its continuous-time phase. */
typedef enum {
    MODE_INSTANTIATED,
    MODE_INITIALIZATION,
    MODE_EVENT,
    MODE_STEP,
    MODE_CONTINUOUS_TIME,
    MODE_TERMINATED,
    MODE_FATAL
} fmi3_mode;

#define MODE_BIT(mode) (1u << (mode))

/* Where each kind of call is allowed (FMI 3.0 Co-Simulation and Model Exchange state
 * machines: a Co-Simulation instance is never in Continuous-Time Mode, a Model Exchange one
 * never in Step Mode), one table for every entry point; MODE_FATAL is in none of them. */
#define MODES_RUNNING                                                                          \
    (MODE_BIT(MODE_EVENT) | MODE_BIT(MODE_STEP) | MODE_BIT(MODE_CONTINUOUS_TIME))
#define MODES_ANY                                                                              \
    (MODE_BIT(MODE_INSTANTIATED) | MODE_BIT(MODE_INITIALIZATION) | MODES_RUNNING |             \
     MODE_BIT(MODE_TERMINATED))
#define MODES_GET (MODE_BIT(MODE_INITIALIZATION) | MODES_RUNNING | MODE_BIT(MODE_TERMINATED))
#define MODES_SET (MODE_BIT(MODE_INSTANTIATED) | MODE_BIT(MODE_INITIALIZATION) | MODES_RUNNING)
#define MODES_INITIALIZED MODES_RUNNING
/* Model Exchange */
#define MODES_EVENT_OR_CONTINUOUS (MODE_BIT(MODE_EVENT) | MODE_BIT(MODE_CONTINUOUS_TIME))
#define MODES_MODEL_EVALUATION                                                                 \
    (MODE_BIT(MODE_INITIALIZATION) | MODES_EVENT_OR_CONTINUOUS | MODE_BIT(MODE_TERMINATED))

fmi3_mode fmi3_mode_of(const fmu_instance *inst);
const char *fmi3_mode_name(fmi3_mode mode);

/* Logs that `function` is not allowed in the instance's state; returns NULL. */
fmi3_instance *fmi3_refuse_in_mode(fmi3_instance *inst, const char *function);

/* The instance when the call is allowed in one of the modes in `allowed` (a set of MODE_BIT);
 * otherwise logs why and returns NULL. */
static inline fmi3_instance *fmi3_checked(fmi3Instance instance, const char *function,
                                          unsigned allowed)
{
    fmi3_instance *inst = instance;
    if (inst == NULL)
        return NULL;
    if ((allowed & MODE_BIT(fmi3_mode_of(&inst->core))) == 0)
        return fmi3_refuse_in_mode(inst, function);
    return inst;
}

/* The core's status as FMI 3.0's: the boundary every fmi3 entry point returns through. */
fmi3Status fmi3_status(fmu_status status);

/* Variables FMI 3.0 adds after the framework's table (model then back-end variables, n of
 * them): the independent variable time, then one Float64 per internal event indicator, which
 * ModelStructure lists as <EventIndicator>. */
static inline fmi3ValueReference fmi3_time_vr(size_t n_variables)
{
    return (fmi3ValueReference)n_variables;
}

static inline fmi3ValueReference fmi3_indicator_vr(size_t n_variables, size_t indicator)
{
    return (fmi3ValueReference)(n_variables + 1 + indicator);
}

/* The model's clocks follow the event indicators. */
static inline fmi3ValueReference fmi3_clock_vr(size_t n_variables, size_t n_indicators,
                                               size_t clock)
{
    return (fmi3ValueReference)(n_variables + 1 + n_indicators + clock);
}

#define FMI3_INDICATOR_NAME "event_indicator_%zu"

#endif
