/* The FMI 1.0 modelDescription.xml of the describe tool: the same variable table as FMI 2.0
 * (same value references) in FMI 1.0's words, for one interface (an FMI 1.0 FMU has one):
 * Co-Simulation declares Implementation/CoSimulation_StandAlone, Model Exchange nothing. */
#include "describe_xml.h"
#include "fmu_guid.h"
#include "fmu_solver.h"

static const char *const type_names[] = {"Real", "Integer", "Boolean"};

/* FMI 1.0 has parameters as a variability (set before initialization only) and internal
 * variables where FMI 2.0 has locals. */
static void write_variable(FILE *out, const model_variable *v, size_t vr)
{
    int parameter = v->causality == CAUSALITY_PARAMETER || v->variability == VARIABILITY_FIXED ||
                    v->variability == VARIABILITY_TUNABLE;
    const char *causality = v->causality == CAUSALITY_INPUT    ? "input"
                            : v->causality == CAUSALITY_OUTPUT ? "output"
                                                               : "internal";
    const char *variability = parameter ? "parameter" : variability_names[v->variability];
    fputs("    <ScalarVariable name=\"", out);
    write_escaped(out, v->name);
    fprintf(out, "\" valueReference=\"%zu\" variability=\"%s\" causality=\"%s\"", vr,
            variability, causality);
    fputs(" description=\"", out);
    write_escaped(out, v->description);
    fprintf(out, "\">\n      <%s", type_names[v->type]);
    if (v->type == TYPE_REAL && v->unit != NULL)
        fprintf(out, " unit=\"%s\"", v->unit);
    if (v->initial == INITIAL_EXACT || v->causality == CAUSALITY_INPUT) {
        fputs(" start=\"", out);
        if (v->declared_start != NULL)
            write_escaped(out, v->declared_start);
        else if (v->type == TYPE_REAL)
            write_real(out, v->start);
        else if (v->type == TYPE_INTEGER)
            fprintf(out, "%d", (int)v->start);
        else
            fputs(v->start != 0.0 ? "true" : "false", out);
        fputs("\" fixed=\"true\"", out);
    }
    fputs("/>\n    </ScalarVariable>\n", out);
}

int write_description_fmi1(FILE *out, const char *model_identifier, int co_simulation)
{
    variable_list list;
    if (collect(&list) != 0)
        return -1;
    char guid[FMU_GUID_LENGTH];
    fmu_guid(guid);
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", out);
    fprintf(out,
            "<fmiModelDescription fmiVersion=\"1.0\" modelName=\"%s\" modelIdentifier=\"%s\"\n"
            "  guid=\"%s\" description=\"",
            fmu_model.name, model_identifier, guid);
    write_escaped(out, fmu_model.description);
    fprintf(out, " (%s back-end, FMI 1.0 %s)\"\n", fmu_solver_name,
            co_simulation ? "Co-Simulation" : "Model Exchange");
    fputs("  generationTool=\"syssimx FMU framework\" variableNamingConvention=\"structured\"\n",
          out);
    fprintf(out, "  numberOfContinuousStates=\"%zu\" numberOfEventIndicators=\"%zu\">\n",
            co_simulation ? (size_t)0 : fmu_model.n_states,
            co_simulation ? (size_t)0 : fmu_model.n_event_indicators);
    fputs("  <DefaultExperiment startTime=\"0\" stopTime=\"", out);
    write_real(out, fmu_model.default_stop_time);
    fputs("\"/>\n  <ModelVariables>\n", out);
    for (size_t vr = 0; vr < list.count; ++vr)
        write_variable(out, list.rows[vr], vr);
    fputs("  </ModelVariables>\n", out);
    if (co_simulation)
        fputs("  <Implementation>\n    <CoSimulation_StandAlone>\n"
              "      <Capabilities canHandleVariableCommunicationStepSize=\"true\"\n"
              "        canHandleEvents=\"true\" canNotUseMemoryManagementFunctions=\"true\"/>\n"
              "    </CoSimulation_StandAlone>\n  </Implementation>\n",
              out);
    fputs("</fmiModelDescription>\n", out);
    return 0;
}
