/* The engine's FMI 3.0 type table (ssx_fmi3_variables) read from a modelDescription.xml with
 * the reader's XML tokenizer, for a caller without Python (a plan's builder): every scalar
 * Float64 ... UInt64, Boolean and Enumeration (an Int64) variable once per value reference, in
 * document order, and how a Co-Simulation instance is made. Array variables (those with
 * Dimension elements), clocks and intermediate-update inputs are left out: a plan lists them
 * (fmi3_element, fmi3_clock, fmi3_intermediate records). */
#ifndef SSX_FMI3_TYPE_TABLE_H
#define SSX_FMI3_TYPE_TABLE_H

#include <stddef.h>

typedef struct {
    unsigned int *vr;
    unsigned char *type; /* ssx_fmi3_type */
    char **name;
    size_t n;
    int has_event_mode;   /* CoSimulation hasEventMode */
    int may_return_early; /* canReturnEarlyAfterIntermediateUpdate or mightReturnEarlyFromDoStep */
} fmi3_type_table;

/* 0, or -1 with the reason (and its line) in error. */
int fmi3_type_table_read(const char *xml, size_t size, fmi3_type_table *out, char *error,
                         size_t error_size);
void fmi3_type_table_free(fmi3_type_table *table);

#endif
