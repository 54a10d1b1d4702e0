/* What the FMI 2.0 and FMI 3.0 modelDescription writers share: the variable table, units,
 * numbers and escaped text. */
#include "describe_xml.h"

#include <stdlib.h>
#include <string.h>

#include "fmu_log.h"
#include "fmu_solver.h"
#include "fmu_units.h"

const char *const causality_names[] = {"parameter", "input", "output", "local"};
const char *const variability_names[] = {"fixed", "tunable", "discrete", "continuous"};


void write_escaped(FILE *out, const char *text)
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
int collect(variable_list *list)
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
void write_real(FILE *out, double value)
{
    char text[32];
    for (int digits = 15; digits <= 17; ++digits) {
        snprintf(text, sizeof text, "%.*g", digits, value);
        if (strtod(text, NULL) == value)
            break;
    }
    fputs(text, out);
}

void write_units(FILE *out, const variable_list *list)
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

int is_state(size_t vr)
{
    for (size_t i = 0; i < fmu_model.n_states; ++i)
        if (fmu_model.state_vrs[i] == vr)
            return 1;
    return 0;
}

void write_log_categories(FILE *out, const char *const descriptions[LOG_CATEGORY_COUNT])
{
    fputs("  <LogCategories>\n", out);
    for (int i = 0; i < LOG_CATEGORY_COUNT; ++i)
        fprintf(out, "    <Category name=\"%s\" description=\"%s\"/>\n", fmu_log_category_names[i],
                descriptions[i]);
    fputs("  </LogCategories>\n", out);
}

void write_default_experiment(FILE *out)
{
    fputs("  <DefaultExperiment startTime=\"0\" stopTime=\"", out);
    write_real(out, fmu_model.default_stop_time);
    fputs("\" stepSize=\"", out);
    write_real(out, fmu_model.default_step_size);
    fputs("\"/>\n", out);
}
