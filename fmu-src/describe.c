/* The describe tool: writes modelDescription.xml for the model and back-end it is linked with.
 * Usage: describe <modelIdentifier> <output.xml>. It fails on an inconsistent table, so a broken
 * model cannot be packaged. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu_guid.h"
#include "fmu_log.h"
#include "fmu_solver.h"
#include "fmu_units.h"
#include "model.h"

static const char *const causality_names[] = {"parameter", "input", "output", "local"};
static const char *const variability_names[] = {"fixed", "tunable", "discrete", "continuous"};
static const char *const type_names[] = {"Real", "Integer", "Boolean"};

typedef struct {
    const model_variable *rows[256];
    size_t count;
} variable_list;

static void write_escaped(FILE *out, const char *text)
{
    for (const char *c = text ? text : ""; *c != '\0'; ++c) {
        switch (*c) {
        case '&': fputs("&amp;", out); break;
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '"': fputs("&quot;", out); break;
        default: fputc(*c, out);
        }
    }
}

/* All variables, model first then back-end, with value reference = position. */
static int collect(variable_list *list)
{
    list->count = 0;
    size_t capacity = sizeof list->rows / sizeof *list->rows;
    if (fmu_model.n_variables + fmu_solver_variable_count > capacity) {
        fprintf(stderr, "more than %zu variables: enlarge variable_list\n", capacity);
        return -1;
    }
    for (size_t i = 0; i < fmu_model.n_variables; ++i) {
        if (fmu_model.variables[i].vr != i) {
            fprintf(stderr, "variable %s: value reference %u is not its row %zu\n",
                    fmu_model.variables[i].name, fmu_model.variables[i].vr, i);
            return -1;
        }
        list->rows[list->count++] = &fmu_model.variables[i];
    }
    for (size_t i = 0; i < fmu_solver_variable_count; ++i)
        list->rows[list->count++] = &fmu_solver_variables[i];
    for (size_t i = 0; i < list->count; ++i)
        if (list->rows[i]->unit != NULL && fmu_unit(list->rows[i]->unit) == NULL) {
            fprintf(stderr, "variable %s: unit %s has no SI definition\n", list->rows[i]->name,
                    list->rows[i]->unit);
            return -1;
        }
    return 0;
}

/* The shortest decimal form that reads back as the same double. */
static void write_real(FILE *out, double value)
{
    char text[32];
    for (int digits = 15; digits <= 17; ++digits) {
        snprintf(text, sizeof text, "%.*g", digits, value);
        if (strtod(text, NULL) == value)
            break;
    }
    fputs(text, out);
}

static void write_units(FILE *out, const variable_list *list)
{
    const char *written[64];
    size_t n_written = 0;
    int opened = 0;
    for (size_t i = 0; i < list->count; ++i) {
        const char *unit = list->rows[i]->unit;
        if (unit == NULL)
            continue;
        int seen = 0;
        for (size_t j = 0; j < n_written; ++j)
            seen |= strcmp(written[j], unit) == 0;
        if (seen || n_written == sizeof written / sizeof *written)
            continue;
        written[n_written++] = unit;
        if (!opened) {
            fputs("  <UnitDefinitions>\n", out);
            opened = 1;
        }
        const unit_definition *def = fmu_unit(unit);
        fprintf(out, "    <Unit name=\"%s\">\n      <BaseUnit", unit);
        if (def->kg)
            fprintf(out, " kg=\"%d\"", def->kg);
        if (def->m)
            fprintf(out, " m=\"%d\"", def->m);
        if (def->s)
            fprintf(out, " s=\"%d\"", def->s);
        if (def->rad)
            fprintf(out, " rad=\"%d\"", def->rad);
        if (def->factor != 1.0) {
            fputs(" factor=\"", out);
            write_real(out, def->factor);
            fputc('"', out);
        }
        fputs("/>\n    </Unit>\n", out);
    }
    if (opened)
        fputs("  </UnitDefinitions>\n", out);
}

static void write_variable(FILE *out, const model_variable *v, size_t vr)
{
    fputs("    <ScalarVariable name=\"", out);
    write_escaped(out, v->name);
    fprintf(out, "\" valueReference=\"%zu\" causality=\"%s\" variability=\"%s\"", vr,
            causality_names[v->causality], variability_names[v->variability]);
    if (v->initial == INITIAL_EXACT)
        fputs(" initial=\"exact\"", out);
    else if (v->initial == INITIAL_CALCULATED)
        fputs(" initial=\"calculated\"", out);
    fputs(" description=\"", out);
    write_escaped(out, v->description);
    fprintf(out, "\">\n      <%s", type_names[v->type]);
    if (v->type == TYPE_REAL && v->unit != NULL)
        fprintf(out, " unit=\"%s\"", v->unit);
    if (v->derivative_of >= 0)
        fprintf(out, " derivative=\"%d\"", v->derivative_of + 1);
    int has_start = v->initial == INITIAL_EXACT || v->causality == CAUSALITY_INPUT;
    if (has_start && v->declared_start != NULL) {
        fputs(" start=\"", out);
        write_escaped(out, v->declared_start);
        fputc('"', out);
    }
    else if (has_start) {
        if (v->type == TYPE_REAL) {
            fputs(" start=\"", out);
            write_real(out, v->start);
            fputc('"', out);
        }
        else if (v->type == TYPE_INTEGER)
            fprintf(out, " start=\"%d\"", (int)v->start);
        else
            fprintf(out, " start=\"%s\"", v->start != 0.0 ? "true" : "false");
    }
    fputs("/>\n    </ScalarVariable>\n", out);
}

static void write_unknown(FILE *out, size_t vr, const int *depends)
{
    fprintf(out, "      <Unknown index=\"%zu\"", vr + 1);
    if (depends != NULL) {
        fputs(" dependencies=\"", out);
        for (const int *d = depends; *d != DEPENDS_END; ++d)
            fprintf(out, d == depends ? "%d" : " %d", *d + 1);
        fputc('"', out);
    }
    fputs("/>\n", out);
}

static int is_state(size_t vr)
{
    for (size_t i = 0; i < fmu_model.n_states; ++i)
        if (fmu_model.state_vrs[i] == vr)
            return 1;
    return 0;
}

static void write_structure(FILE *out, const variable_list *list)
{
    fputs("  <ModelStructure>\n", out);
    int any_output = 0, any_derivative = 0;
    for (size_t vr = 0; vr < list->count; ++vr) {
        any_output |= list->rows[vr]->causality == CAUSALITY_OUTPUT;
        any_derivative |= list->rows[vr]->derivative_of >= 0;
    }
    if (any_output) {
        fputs("    <Outputs>\n", out);
        for (size_t vr = 0; vr < list->count; ++vr)
            if (list->rows[vr]->causality == CAUSALITY_OUTPUT)
                write_unknown(out, vr, list->rows[vr]->depends);
        fputs("    </Outputs>\n", out);
    }
    if (any_derivative) {
        /* in state order: the order of <Derivatives> defines the state vector */
        fputs("    <Derivatives>\n", out);
        for (size_t i = 0; i < fmu_model.n_states; ++i)
            for (size_t vr = 0; vr < list->count; ++vr)
                if (list->rows[vr]->derivative_of == (int)fmu_model.state_vrs[i])
                    write_unknown(out, vr, list->rows[vr]->depends);
        fputs("    </Derivatives>\n", out);
    }
    /* outputs computed at initialization, plus states and derivatives (both interfaces) */
    fputs("    <InitialUnknowns>\n", out);
    for (size_t vr = 0; vr < list->count; ++vr) {
        const model_variable *v = list->rows[vr];
        int listed = (v->causality == CAUSALITY_OUTPUT || v->derivative_of >= 0 || is_state(vr)) &&
                     v->initial == INITIAL_CALCULATED;
        if (listed)
            write_unknown(out, vr, v->initial_depends);
    }
    fputs("    </InitialUnknowns>\n  </ModelStructure>\n", out);
}

static int write_description(FILE *out, const char *model_identifier)
{
    variable_list list;
    if (collect(&list) != 0)
        return -1;
    char guid[FMU_GUID_LENGTH];
    fmu_guid(guid);
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", out);
    fprintf(out, "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"%s\" guid=\"%s\"\n",
            fmu_model.name, guid);
    fputs("  description=\"", out);
    write_escaped(out, fmu_model.description);
    fprintf(out, " (%s back-end)\"\n", fmu_solver_name);
    fputs("  generationTool=\"syssimx FMU framework\" variableNamingConvention=\"structured\"\n",
          out);
    fprintf(out, "  numberOfEventIndicators=\"%zu\">\n", fmu_model.n_event_indicators);
    const char *directional = fmu_model.partial_derivative != NULL ? "true" : "false";
    /* one binary serves both interfaces; fmi2CompletedIntegratorStep never has anything to do */
    fprintf(out,
            "  <ModelExchange modelIdentifier=\"%s\" completedIntegratorStepNotNeeded=\"true\"\n"
            "    canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\"\n"
            "    canNotUseMemoryManagementFunctions=\"true\"\n"
            "    providesDirectionalDerivative=\"%s\"/>\n",
            model_identifier, directional);
    fprintf(out,
            "  <CoSimulation modelIdentifier=\"%s\" canHandleVariableCommunicationStepSize=\"true\"\n"
            "    canGetAndSetFMUstate=\"true\" canSerializeFMUstate=\"true\"\n"
            "    canNotUseMemoryManagementFunctions=\"true\" canInterpolateInputs=\"false\"\n"
            "    providesDirectionalDerivative=\"%s\"/>\n",
            model_identifier, directional);
    write_units(out, &list);
    fputs("  <LogCategories>\n", out);
    for (int i = 0; i < LOG_CATEGORY_COUNT; ++i)
        fprintf(out, "    <Category name=\"%s\" description=\"%s\"/>\n", fmu_log_category_names[i],
                fmu_log_category_descriptions[i]);
    fputs("  </LogCategories>\n", out);
    fputs("  <DefaultExperiment startTime=\"0\" stopTime=\"", out);
    write_real(out, fmu_model.default_stop_time);
    fputs("\" stepSize=\"", out);
    write_real(out, fmu_model.default_step_size);
    fputs("\"/>\n", out);
    fputs("  <ModelVariables>\n", out);
    for (size_t vr = 0; vr < list.count; ++vr)
        write_variable(out, list.rows[vr], vr);
    fputs("  </ModelVariables>\n", out);
    write_structure(out, &list);
    fputs("</fmiModelDescription>\n", out);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s <modelIdentifier> <output.xml>\n", argv[0]);
        return 2;
    }
    FILE *out = fopen(argv[2], "w");
    if (out == NULL) {
        perror(argv[2]);
        return 1;
    }
    int failed = write_description(out, argv[1]) != 0;
    failed |= fclose(out) != 0;
    if (failed)
        remove(argv[2]);
    return failed;
}
