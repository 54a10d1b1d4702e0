/* Reading the export map (export_map.h): a file of the FMU's own, still bounded and checked. */
#include "export_map.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_VARIABLES = 1 << 20, MAX_LINE = 4096 };

static const char *const role_names[] = {"input", "output", "parameter", "events",
                                         "last_event_time"};

static const char *const type_names[] = {"real", "integer", "boolean"};

/* The index of `word` in `names`, or -1. */
static int word_index(const char *word, const char *const *names, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        if (strcmp(word, names[k]) == 0) {
            return (int)k;
        }
    }
    return -1;
}

static int read_line(export_map *map, const char *line, size_t *capacity)
{
    char word[32];
    if (sscanf(line, "%31s", word) != 1 || word[0] == '#') {
        return 0; /* blank or comment */
    }
    if (strcmp(word, "token") == 0) {
        const char *open = strchr(line, '"');
        const char *close = open != NULL ? strchr(open + 1, '"') : NULL;
        if (close == NULL || (size_t)(close - open - 1) >= sizeof map->token) {
            return -1;
        }
        memcpy(map->token, open + 1, (size_t)(close - open - 1));
        map->token[close - open - 1] = '\0';
        return 0;
    }
    if (strcmp(word, "step") == 0) {
        return sscanf(line, "step %lf", &map->step) == 1 && map->step >= 0.0 ? 0 : -1;
    }
    if (strcmp(word, "variable") != 0) {
        return -1;
    }
    export_variable variable;
    char role[32];
    char type[32];
    int name_at = 0;
    if (sscanf(line, "variable %u %31s %d %d %31s %lf %n", &variable.vr, role,
               &variable.component, &variable.index, type, &variable.start, &name_at) != 6 ||
        name_at == 0 || line[name_at] == '\0' || map->n >= MAX_VARIABLES ||
        export_map_find(map, variable.vr) >= 0) {
        return -1;
    }
    int role_index = word_index(role, role_names, sizeof role_names / sizeof role_names[0]);
    int type_index = word_index(type, type_names, sizeof type_names / sizeof type_names[0]);
    if (role_index < 0 || type_index < 0) {
        return -1;
    }
    variable.role = (export_role)role_index;
    variable.type = (export_type)type_index;
    if (map->n == *capacity) {
        size_t grown = *capacity ? 2 * *capacity : 16;
        export_variable *more = realloc(map->variables, grown * sizeof *more);
        if (more == NULL) {
            return -1;
        }
        map->variables = more;
        *capacity = grown;
    }
    size_t name_size = strlen(line + name_at) + 1;
    variable.name = malloc(name_size);
    if (variable.name == NULL) {
        return -1;
    }
    memcpy(variable.name, line + name_at, name_size);
    map->variables[map->n++] = variable;
    return 0;
}

int export_map_read(const char *text, size_t size, export_map *map, char *error, size_t error_size)
{
    memset(map, 0, sizeof *map);
    size_t capacity = 0;
    size_t line_number = 0;
    for (size_t at = 0; at < size;) {
        const char *end = memchr(text + at, '\n', size - at);
        size_t length = end != NULL ? (size_t)(end - (text + at)) : size - at;
        char line[MAX_LINE];
        line_number++;
        int ok = length < sizeof line;
        if (ok) {
            memcpy(line, text + at, length);
            line[length] = '\0';
            ok = line_number == 1 ? strncmp(line, "syssimx-export 1", 16) == 0
                                  : read_line(map, line, &capacity) == 0;
        }
        if (!ok) {
            snprintf(error, error_size, "export map, line %zu: not understood", line_number);
            export_map_free(map);
            return -1;
        }
        at += length + 1;
    }
    if (line_number == 0 || map->token[0] == '\0') {
        snprintf(error, error_size, "export map: no %s", line_number ? "token" : "header");
        export_map_free(map);
        return -1;
    }
    return 0;
}

void export_map_free(export_map *map)
{
    for (size_t k = 0; k < map->n; k++) {
        free(map->variables[k].name);
    }
    free(map->variables);
    map->variables = NULL;
    map->n = 0;
}

long export_map_find(const export_map *map, unsigned int vr)
{
    /* the exporter numbers the variables 1, 2, ... in order */
    if (vr >= 1 && vr <= map->n && map->variables[vr - 1].vr == vr) {
        return (long)vr - 1;
    }
    for (size_t k = 0; k < map->n; k++) {
        if (map->variables[k].vr == vr) {
            return (long)k;
        }
    }
    return -1;
}
