/* The describe tool: writes modelDescription.xml for the model and back-end it is linked with.
 * Usage: describe <modelIdentifier> <output.xml> [2.0|3.0|1.0-cs|1.0-me] (the FMI version, 2.0
 * by default; FMI 1.0 describes one interface).
 * It fails on an inconsistent table, so a broken model cannot be packaged. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "describe_xml.h"
#include "fmu_guid.h"
#include "fmu_interpolation.h"
#include "fmu_solver.h"
#include "model.h"

static const char *const type_names[] = {"Real", "Integer", "Boolean"};

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
            "    canNotUseMemoryManagementFunctions=\"true\" canInterpolateInputs=\"true\"\n"
            "    maxOutputDerivativeOrder=\"%d\" providesDirectionalDerivative=\"%s\"/>\n",
            model_identifier, FMU_MAX_OUTPUT_DERIVATIVE_ORDER, directional);
    write_units(out, &list);
    write_log_categories(out, fmu_log_category_descriptions);
    write_default_experiment(out);
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
    const char *version = argc == 4 ? argv[3] : "2.0";
    int fmi3 = strcmp(version, "3.0") == 0;
    int fmi1_cs = strcmp(version, "1.0-cs") == 0, fmi1_me = strcmp(version, "1.0-me") == 0;
    if (argc < 3 || argc > 4 ||
        !(fmi3 || fmi1_cs || fmi1_me || strcmp(version, "2.0") == 0)) {
        fprintf(stderr, "usage: %s <modelIdentifier> <output.xml> [2.0|3.0|1.0-cs|1.0-me]\n",
                argv[0]);
        return 2;
    }
    FILE *out = fopen(argv[2], "w");
    if (out == NULL) {
        perror(argv[2]);
        return 1;
    }
    int written = fmi3                ? write_description_fmi3(out, argv[1])
                  : fmi1_cs || fmi1_me ? write_description_fmi1(out, argv[1], fmi1_cs)
                                       : write_description(out, argv[1]);
    int failed = written != 0;
    failed |= fclose(out) != 0;
    if (failed)
        remove(argv[2]);
    return failed;
}
