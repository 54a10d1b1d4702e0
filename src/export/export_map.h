/* The export map of an exported FMU (resources/export.map): which of its value references is
 * which port or parameter of which member, the token it was generated with, and the inner
 * communication step. Text, one record a line:
 *   syssimx-export 1
 *   token "TOKEN"
 *   step DT                      (0: each doStep is one communication step of the system)
 *   variable VR ROLE COMPONENT INDEX TYPE START NAME
 * ROLE is input, output (INDEX: the engine's port index of the member COMPONENT), parameter
 * (INDEX: the member FMU's value reference), events or last_event_time (the system's own;
 * COMPONENT and INDEX -1). TYPE is real, integer or boolean; START the exported start (nan:
 * none); NAME, the rest of the line, is
 * the variable's name in the modelDescription (for messages). */
#ifndef SSX_EXPORT_MAP_H
#define SSX_EXPORT_MAP_H

#include <stddef.h>

typedef enum {
    EXPORT_INPUT,
    EXPORT_OUTPUT,
    EXPORT_PARAMETER,
    EXPORT_EVENTS,
    EXPORT_LAST_EVENT_TIME
} export_role;

typedef enum { EXPORT_REAL, EXPORT_INTEGER, EXPORT_BOOLEAN } export_type;

typedef struct {
    unsigned int vr;
    export_role role;
    int component;
    int index;
    export_type type;
    double start;
    char *name;
} export_variable;

typedef struct {
    char token[128];
    double step;
    size_t n;
    export_variable *variables;
} export_map;

/* 0, or -1 with the reason (naming the line) in error; a map read is freed by
 * export_map_free, a failed read leaves nothing to free. */
int export_map_read(const char *text, size_t size, export_map *map, char *error, size_t error_size);
void export_map_free(export_map *map);
/* The variable of value reference vr, or -1. */
long export_map_find(const export_map *map, unsigned int vr);

#endif
