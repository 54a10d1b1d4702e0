/* FMI 3.0 type tables from modelDescription.xml (the contract is in fmi3_type_table.h). */
#include "fmi3_type_table.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "syssimx_engine.h"
#include "xml_tokenizer.h"

/* The elements of ModelVariables the engine exchanges, by their ssx_fmi3_type. */
static const struct {
    const char *tag;
    unsigned char type;
} exchanged[] = {
    {"Float64", SSX_FMI3_FLOAT64}, {"Float32", SSX_FMI3_FLOAT32}, {"Int8", SSX_FMI3_INT8},
    {"UInt8", SSX_FMI3_UINT8},     {"Int16", SSX_FMI3_INT16},     {"UInt16", SSX_FMI3_UINT16},
    {"Int32", SSX_FMI3_INT32},     {"UInt32", SSX_FMI3_UINT32},   {"Int64", SSX_FMI3_INT64},
    {"UInt64", SSX_FMI3_UINT64},   {"Boolean", SSX_FMI3_BOOLEAN},
    {"Enumeration", SSX_FMI3_INT64}, /* FMI 3.0 exchanges an enumeration as an Int64 */
};

typedef struct {
    xml_tokenizer xml;
    fmi3_type_table *table;
    size_t capacity;
    size_t depth;
    int root_seen;
    int in_variables;
    int pending;       /* a variable element is open at depth 3 */
    int has_dimension; /* and holds a Dimension */
    unsigned int pending_vr;
    unsigned char pending_type;
    char *pending_name;
    char *error;
    size_t error_size;
    int failed;
} reader;

static bool refuse(reader *r, size_t line, const char *what)
{
    if (!r->failed && r->error != NULL && r->error_size > 0) {
        snprintf(r->error, r->error_size, "modelDescription.xml line %zu: %s", line, what);
    }
    r->failed = 1;
    return false;
}

static int is_true(slice value)
{
    return slice_is(value, "true");
}

static char *decoded(slice value)
{
    char *out = malloc(value.length + 1);
    if (out != NULL) {
        out[xml_decode(out, value)] = '\0';
    }
    return out;
}

static bool start_variable(reader *r, unsigned char type, size_t line)
{
    r->pending = 1;
    r->has_dimension = 0;
    r->pending_type = type;
    int found_vr = 0;
    for (size_t i = 0; i < r->xml.attribute_count; ++i) {
        slice name = r->xml.attributes[i].name, value = r->xml.attributes[i].value;
        if (slice_is(name, "name")) {
            free(r->pending_name);
            r->pending_name = decoded(value);
            if (r->pending_name == NULL) {
                return refuse(r, line, "out of memory");
            }
        } else if (slice_is(name, "valueReference")) {
            char digits[16];
            if (value.length == 0 || value.length >= sizeof digits) {
                return refuse(r, line, "a valueReference that is no 32-bit number");
            }
            memcpy(digits, value.at, value.length);
            digits[value.length] = '\0';
            char *stop = NULL;
            unsigned long long vr = strtoull(digits, &stop, 10);
            if (*stop != '\0' || digits[0] == '-' || vr > UINT_MAX) {
                return refuse(r, line, "a valueReference that is no 32-bit number");
            }
            r->pending_vr = (unsigned int)vr;
            found_vr = 1;
        }
    }
    if (!found_vr || r->pending_name == NULL) {
        return refuse(r, line, "a variable without a name or a valueReference");
    }
    return true;
}

static bool start_element(void *user, slice tag, size_t line)
{
    reader *r = user;
    ++r->depth;
    if (r->depth == 1) {
        slice version = {0};
        for (size_t i = 0; i < r->xml.attribute_count; ++i) {
            if (slice_is(r->xml.attributes[i].name, "fmiVersion")) {
                version = r->xml.attributes[i].value;
            }
        }
        if (!slice_is(tag, "fmiModelDescription") || version.length < 2 ||
            memcmp(version.at, "3.", 2) != 0) {
            return refuse(r, line, "not an FMI 3.0 fmiModelDescription");
        }
        r->root_seen = 1;
    } else if (r->depth == 2 && slice_is(tag, "CoSimulation")) {
        for (size_t i = 0; i < r->xml.attribute_count; ++i) {
            slice name = r->xml.attributes[i].name, value = r->xml.attributes[i].value;
            if (slice_is(name, "hasEventMode")) {
                r->table->has_event_mode = is_true(value);
            } else if (slice_is(name, "canReturnEarlyAfterIntermediateUpdate") ||
                       slice_is(name, "mightReturnEarlyFromDoStep")) {
                r->table->may_return_early |= is_true(value);
            }
        }
    } else if (r->depth == 2) {
        r->in_variables = slice_is(tag, "ModelVariables");
    } else if (r->depth == 3 && r->in_variables) {
        for (size_t k = 0; k < sizeof exchanged / sizeof exchanged[0]; ++k) {
            if (slice_is(tag, exchanged[k].tag)) {
                return start_variable(r, exchanged[k].type, line);
            }
        }
    } else if (r->depth == 4 && r->pending && slice_is(tag, "Dimension")) {
        r->has_dimension = 1;
    }
    return true;
}

static bool commit_variable(reader *r)
{
    fmi3_type_table *t = r->table;
    if (t->n == r->capacity) {
        size_t capacity = r->capacity ? 2 * r->capacity : 64;
        unsigned int *vr = realloc(t->vr, capacity * sizeof *vr);
        if (vr != NULL) {
            t->vr = vr;
        }
        unsigned char *type = realloc(t->type, capacity * sizeof *type);
        if (type != NULL) {
            t->type = type;
        }
        char **name = realloc(t->name, capacity * sizeof *name);
        if (name != NULL) {
            t->name = name;
        }
        if (vr == NULL || type == NULL || name == NULL) {
            return refuse(r, r->xml.line, "out of memory");
        }
        r->capacity = capacity;
    }
    t->vr[t->n] = r->pending_vr;
    t->type[t->n] = r->pending_type;
    t->name[t->n++] = r->pending_name;
    r->pending_name = NULL;
    return true;
}

static bool end_element(void *user)
{
    reader *r = user;
    if (r->depth == 3 && r->pending) {
        r->pending = 0;
        if (!r->has_dimension && !commit_variable(r)) {
            return false;
        }
        free(r->pending_name);
        r->pending_name = NULL;
    } else if (r->depth == 2) {
        r->in_variables = 0;
    }
    --r->depth;
    return true;
}

/* An alias shares its variable's value reference: the first variable of each stays. */
typedef struct {
    unsigned int vr;
    size_t position;
} keyed;

static int by_vr_then_position(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    if (x->vr != y->vr) {
        return x->vr < y->vr ? -1 : 1;
    }
    return x->position < y->position ? -1 : x->position > y->position;
}

static int drop_aliases(fmi3_type_table *t)
{
    keyed *keys = malloc((t->n ? t->n : 1) * sizeof *keys);
    unsigned char *keep = calloc(t->n ? t->n : 1, 1);
    if (keys == NULL || keep == NULL) {
        free(keys);
        free(keep);
        return -1;
    }
    for (size_t k = 0; k < t->n; ++k) {
        keys[k] = (keyed){t->vr[k], k};
    }
    qsort(keys, t->n, sizeof *keys, by_vr_then_position);
    for (size_t k = 0; k < t->n; ++k) {
        keep[keys[k].position] = k == 0 || keys[k].vr != keys[k - 1].vr;
    }
    size_t kept = 0;
    for (size_t k = 0; k < t->n; ++k) {
        if (keep[k]) {
            t->vr[kept] = t->vr[k];
            t->type[kept] = t->type[k];
            t->name[kept++] = t->name[k];
        } else {
            free(t->name[k]);
        }
    }
    t->n = kept;
    free(keys);
    free(keep);
    return 0;
}

int fmi3_type_table_read(const char *xml, size_t size, fmi3_type_table *out, char *error,
                         size_t error_size)
{
    memset(out, 0, sizeof *out);
    ssx_md_error xml_error;
    memset(&xml_error, 0, sizeof xml_error);
    reader r = {.table = out, .error = error, .error_size = error_size};
    r.xml = (xml_tokenizer){.at = xml, .end = xml + size, .line = 1, .error = &xml_error,
                            .handler = {start_element, end_element}, .user = &r};
    int read = xml_read_document(&r.xml);
    if (!read && !r.failed) {
        char detail[256];
        snprintf(detail, sizeof detail, "not well-formed XML: %s", xml_error.detail);
        refuse(&r, xml_error.line, detail);
    } else if (read && !r.root_seen) {
        refuse(&r, 1, "no fmiModelDescription");
    }
    xml_tokenizer_free(&r.xml);
    free(r.pending_name);
    free(xml_error.subject);
    free(xml_error.text);
    free(xml_error.other);
    if (!r.failed && drop_aliases(out) != 0) {
        refuse(&r, 1, "out of memory");
    }
    if (r.failed) {
        fmi3_type_table_free(out);
        return -1;
    }
    return 0;
}

void fmi3_type_table_free(fmi3_type_table *table)
{
    for (size_t k = 0; k < table->n; ++k) {
        free(table->name[k]);
    }
    free(table->vr);
    free(table->type);
    free(table->name);
    memset(table, 0, sizeof *table);
}
