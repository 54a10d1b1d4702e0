/* What the modelDescription writers of the describe tool (FMI 1.0, 2.0, 3.0) share. */
#ifndef SYSSIMX_DESCRIBE_XML_H
#define SYSSIMX_DESCRIBE_XML_H

#include <stdio.h>

#include "fmu_log.h"
#include "model.h"

extern const char *const causality_names[];
extern const char *const variability_names[];

typedef struct {
    const model_variable *rows[256];
    size_t count;
} variable_list;

/* All variables, model first then back-end, with value reference = position; -1 after a
 * message on stderr when the table is inconsistent. */
int collect(variable_list *list);
void write_escaped(FILE *out, const char *text);
/* The shortest decimal form that reads back as the same double. */
void write_real(FILE *out, double value);
/* <UnitDefinitions> with each unit's SI base units, when any variable has a unit. */
void write_units(FILE *out, const variable_list *list);
int is_state(size_t vr);
void write_log_categories(FILE *out, const char *const descriptions[LOG_CATEGORY_COUNT]);
void write_default_experiment(FILE *out);

/* The FMI 3.0 modelDescription (describe_fmi3.c); -1 when the table is inconsistent. */
int write_description_fmi3(FILE *out, const char *model_identifier);
/* The FMI 1.0 modelDescription of one interface (describe_fmi1.c); -1 likewise. */
int write_description_fmi1(FILE *out, const char *model_identifier, int co_simulation);

#endif
