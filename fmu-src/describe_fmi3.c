/* The FMI 3.0 modelDescription.xml of the describe tool: the same variable table as FMI 2.0
 * (same value references), typed Float64/Int32/Boolean, plus the independent variable time and
 * one Float64 per internal event indicator; ModelStructure by value reference. */
#include <string.h>

#include "describe_xml.h"
#include "fmi3_instance.h"
#include "fmu_guid.h"
#include "fmu_interpolation.h"
#include "fmu_solver.h"

static const char *const type_names[] = {"Float64", "Int32", "Boolean"};

static const char *const log_category_descriptions[LOG_CATEGORY_COUNT] = {
    "internal events located and handled by the FMU", "calls that return fmi3Warning",
    "calls that return fmi3Error", "every message"};

static void write_start(FILE *out, const model_variable *v)
{
    fputs(" start=\"", out);
    if (v->declared_start != NULL)
        write_escaped(out, v->declared_start);
    else if (v->type == TYPE_REAL)
        write_real(out, v->start);
    else if (v->type == TYPE_INTEGER)
        fprintf(out, "%d", (int)v->start);
    else
        fputs(v->start != 0.0 ? "true" : "false", out);
    fputc('"', out);
}

static fmi3ValueReference clock_vr(size_t n_variables, size_t clock)
{
    return fmi3_clock_vr(n_variables, fmu_model.n_event_indicators, clock);
}

static void write_variable(FILE *out, const model_variable *v, size_t vr, size_t n_variables)
{
    fprintf(out, "    <%s name=\"", type_names[v->type]);
    write_escaped(out, v->name);
    fprintf(out, "\" valueReference=\"%zu\" causality=\"%s\" variability=\"%s\"", vr,
            causality_names[v->causality], variability_names[v->variability]);
    if (v->initial == INITIAL_EXACT)
        fputs(" initial=\"exact\"", out);
    else if (v->initial == INITIAL_CALCULATED)
        fputs(" initial=\"calculated\"", out);
    fputs(" description=\"", out);
    write_escaped(out, v->description);
    fputc('"', out);
    if (v->type == TYPE_REAL && v->unit != NULL)
        fprintf(out, " unit=\"%s\"", v->unit);
    if (v->derivative_of >= 0)
        fprintf(out, " derivative=\"%d\"", v->derivative_of);
    if (fmi3_intermediate_input(v))
        fputs(" intermediateUpdate=\"true\"", out);
    if (v->clock > 0)
        fprintf(out, " clocks=\"%u\"", clock_vr(n_variables, (size_t)v->clock - 1));
    if (v->initial == INITIAL_EXACT || v->causality == CAUSALITY_INPUT)
        write_start(out, v);
    fputs("/>\n", out);
}

static void write_extra_variables(FILE *out, size_t n_variables)
{
    fprintf(out,
            "    <Float64 name=\"time\" valueReference=\"%u\" causality=\"independent\" "
            "variability=\"continuous\" description=\"simulation time\"/>\n",
            fmi3_time_vr(n_variables));
    for (size_t i = 0; i < fmu_model.n_event_indicators; ++i) {
        fputs("    <Float64 name=\"", out);
        fprintf(out, FMI3_INDICATOR_NAME, i);
        fprintf(out,
                "\" valueReference=\"%u\" causality=\"local\" variability=\"continuous\" "
                "initial=\"calculated\" description=\"internal event indicator %zu: the event "
                "occurs when it falls from above zero to zero or below\"/>\n",
                fmi3_indicator_vr(n_variables, i), i);
    }
    for (size_t i = 0; i < fmu_model.n_clocks; ++i) {
        const model_clock *clock = &fmu_model.clocks[i];
        fputs("    <Clock name=\"", out);
        write_escaped(out, clock->name);
        fprintf(out, "\" valueReference=\"%u\" causality=\"%s\" variability=\"discrete\" ",
                clock_vr(n_variables, i), clock->kind == CLOCK_OUTPUT ? "output" : "input");
        if (clock->kind == CLOCK_PERIODIC) {
            fputs("intervalVariability=\"constant\" intervalDecimal=\"", out);
            write_real(out, clock->interval);
            fputc('"', out);
        } else {
            fprintf(out, "intervalVariability=\"%s\"",
                    clock->kind == CLOCK_COUNTDOWN  ? "countdown"
                    : clock->kind == CLOCK_CHANGING ? "changing"
                                                    : "triggered");
        }
        fputs(" description=\"", out);
        write_escaped(out, clock->description);
        fputs("\"/>\n", out);
    }
}

static void write_unknown(FILE *out, const char *element, size_t vr, const int *depends)
{
    fprintf(out, "    <%s valueReference=\"%zu\"", element, vr);
    if (depends != NULL) {
        fputs(" dependencies=\"", out);
        for (const int *d = depends; *d != DEPENDS_END; ++d)
            fprintf(out, d == depends ? "%d" : " %d", *d);
        fputc('"', out);
    }
    fputs("/>\n", out);
}

static void write_structure(FILE *out, const variable_list *list)
{
    fputs("  <ModelStructure>\n", out);
    for (size_t vr = 0; vr < list->count; ++vr)
        if (list->rows[vr]->causality == CAUSALITY_OUTPUT)
            write_unknown(out, "Output", vr, list->rows[vr]->depends);
    /* an output clock is an output too; it depends on the states through its event */
    for (size_t i = 0; i < fmu_model.n_clocks; ++i)
        if (fmu_model.clocks[i].kind == CLOCK_OUTPUT)
            write_unknown(out, "Output", clock_vr(list->count, i), NULL);
    /* in state order: the order of the derivatives defines the state vector */
    for (size_t i = 0; i < fmu_model.n_states; ++i)
        for (size_t vr = 0; vr < list->count; ++vr)
            if (list->rows[vr]->derivative_of == (int)fmu_model.state_vrs[i])
                write_unknown(out, "ContinuousStateDerivative", vr, list->rows[vr]->depends);
    /* Co-Simulation: outputs computed at initialization, plus states and derivatives */
    for (size_t vr = 0; vr < list->count; ++vr) {
        const model_variable *v = list->rows[vr];
        if ((v->causality == CAUSALITY_OUTPUT || v->derivative_of >= 0 || is_state(vr)) &&
            v->initial == INITIAL_CALCULATED)
            write_unknown(out, "InitialUnknown", vr, v->initial_depends);
    }
    for (size_t i = 0; i < fmu_model.n_clocks; ++i)
        if (fmu_model.clocks[i].kind == CLOCK_OUTPUT)
            write_unknown(out, "InitialUnknown", clock_vr(list->count, i), NULL);
    for (size_t i = 0; i < fmu_model.n_event_indicators; ++i)
        write_unknown(out, "EventIndicator", fmi3_indicator_vr(list->count, i), NULL);
    fputs("  </ModelStructure>\n", out);
}

/* One binary serves both interfaces, as in FMI 2.0; fmi3CompletedIntegratorStep never has
 * anything to do. */
static void write_model_exchange(FILE *out, const char *model_identifier)
{
    fprintf(out,
            "  <ModelExchange modelIdentifier=\"%s\" needsCompletedIntegratorStep=\"false\"\n"
            "    canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\"",
            model_identifier);
    if (fmu_model.partial_derivative != NULL)
        fputs(" providesDirectionalDerivatives=\"true\"", out);
    fputs("/>\n", out);
}

static void write_co_simulation(FILE *out, const char *model_identifier)
{
    /* the importer ticks input clocks in Event Mode */
    int has_events = fmu_model.n_event_indicators > 0 || fmu_model.n_clocks > 0;
    /* the step ends early at an internal event (event mode) or where the model asks to stop */
    int returns_early = !fmu_model.events_at_step_end &&
                        (fmu_model.n_event_indicators > 0 || fmu_model.termination_time != NULL);
    fprintf(out,
            "  <CoSimulation modelIdentifier=\"%s\" canHandleVariableCommunicationStepSize=\"true\"\n"
            "    canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\"",
            model_identifier);
    if (fmu_model.partial_derivative != NULL)
        fputs(" providesDirectionalDerivatives=\"true\"", out);
    /* Output derivatives from the model's equations; the inputs follow the importer's answers
     * to intermediate update inside a step. */
    fprintf(out, "\n    maxOutputDerivativeOrder=\"%d\" providesIntermediateUpdate=\"true\"",
            FMU_MAX_OUTPUT_DERIVATIVE_ORDER);
    /* With event mode the FMU returns early at each internal event of its own accord
     * (mightReturnEarlyFromDoStep). Its intermediate updates never offer an early return, so
     * canReturnEarlyAfterIntermediateUpdate promises nothing beyond that; it is declared for
     * importers that look for it next to hasEventMode. A model with events_at_step_end
     * declares that it never returns early. */
    if (has_events)
        fputs("\n    hasEventMode=\"true\"", out);
    if (fmu_model.events_at_step_end)
        fputs(" mightReturnEarlyFromDoStep=\"false\"", out);
    else if (has_events)
        fputs(" canReturnEarlyAfterIntermediateUpdate=\"true\"", out);
    if (returns_early)
        fputs(" mightReturnEarlyFromDoStep=\"true\"", out);
    fputs("/>\n", out);
}

int write_description_fmi3(FILE *out, const char *model_identifier)
{
    variable_list list;
    if (collect(&list) != 0)
        return -1;
    if (fmu_model.n_clocks > FMI3_MAX_CLOCKS) {
        fprintf(stderr, "%zu clocks: the framework serves at most %d\n", fmu_model.n_clocks,
                FMI3_MAX_CLOCKS);
        return -1;
    }
    char guid[FMU_GUID_LENGTH];
    fmu_guid(guid);
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", out);
    fprintf(out, "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"%s\"\n", fmu_model.name);
    fprintf(out, "  instantiationToken=\"%s\"\n  description=\"", guid);
    write_escaped(out, fmu_model.description);
    fprintf(out, " (%s back-end)\"\n", fmu_solver_name);
    fputs("  generationTool=\"syssimx FMU framework\" variableNamingConvention=\"structured\">\n",
          out);
    write_model_exchange(out, model_identifier);
    write_co_simulation(out, model_identifier);
    write_units(out, &list);
    write_log_categories(out, log_category_descriptions);
    write_default_experiment(out);
    fputs("  <ModelVariables>\n", out);
    for (size_t vr = 0; vr < list.count; ++vr)
        write_variable(out, list.rows[vr], vr, list.count);
    write_extra_variables(out, list.count);
    fputs("  </ModelVariables>\n", out);
    write_structure(out, &list);
    fputs("</fmiModelDescription>\n", out);
    return 0;
}
