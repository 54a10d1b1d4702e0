/* Reading a plan (docs/reference/plan-format.md): line by line, each record checked against
 * its keyword's signature (plan_schema.c) and against what the records before it defined.
 * Bounded: the text, a line, a string and a list each have a limit, memory grows only with
 * what the text holds, and every refusal names the line, the record and the field. */
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plan.h"

enum {
    PLAN_MAX_LINE = 64 << 20,
    PLAN_MAX_STRING = 16 << 20,
    PLAN_MAX_LIST = 1 << 26,
    PLAN_MAX_COMPONENTS = 1 << 20,
    PLAN_MAX_NUMBER = 64, /* characters of one number */
};
#define PLAN_MAX_TEXT ((size_t)256 << 20)
#define PLAN_HEADER "syssimx-plan 1"

typedef struct {
    ssx_plan *plan;
    size_t records_capacity;
    size_t values_capacity;
    size_t pool_capacity;
    size_t components_capacity;
    int64_t *table_rows; /* per component: a table's rows, -1 for any other kind */
    int *fmi_version;    /* per component: an FMU's standard, 0 for any other kind */
    /* the line being read */
    size_t line;
    const char *at;
    const char *end;
    /* where in it, for messages */
    int record;
    int field; /* top-level element of the signature, -1 before the keyword */
    long item; /* item of a list, -1 outside one */
    int last_component;
    char *error;
    size_t error_size;
    int failed;
} reader;

static int refuse(reader *r, const char *format, ...) __attribute__((format(printf, 2, 3)));

/* The name of top-level field `field` of the record being read. */
static void field_name(const reader *r, char *out, size_t out_size)
{
    const char *names = plan_schema[r->record].field_names;
    for (int k = 0; k < r->field && names != NULL; ++k) {
        names = strchr(names, ' ');
        names = names != NULL ? names + 1 : NULL;
    }
    if (names == NULL) {
        snprintf(out, out_size, "?");
        return;
    }
    size_t n = strcspn(names, " ");
    snprintf(out, out_size, "%.*s", (int)n, names);
}

static int refuse(reader *r, const char *format, ...)
{
    if (r->failed) {
        return -1;
    }
    r->failed = 1;
    if (r->error == NULL || r->error_size == 0) {
        return -1;
    }
    char where[160];
    if (r->record < 0) {
        snprintf(where, sizeof where, "line %zu", r->line);
    } else if (r->field < 0) {
        snprintf(where, sizeof where, "line %zu: record '%s'", r->line,
                 plan_schema[r->record].keyword);
    } else {
        char name[64];
        field_name(r, name, sizeof name);
        if (r->item >= 0) {
            snprintf(where, sizeof where, "line %zu: record '%s', field %s (item %ld)", r->line,
                     plan_schema[r->record].keyword, name, r->item + 1);
        } else {
            snprintf(where, sizeof where, "line %zu: record '%s', field %s", r->line,
                     plan_schema[r->record].keyword, name);
        }
    }
    char reason[512];
    va_list args;
    va_start(args, format);
    vsnprintf(reason, sizeof reason, format, args);
    va_end(args);
    snprintf(r->error, r->error_size, "%s: %s", where, reason);
    return -1;
}

/* Grows *array (of *capacity items of `size` bytes) to hold `needed` items. */
static int reserve(reader *r, void **array, size_t *capacity, size_t needed, size_t size)
{
    if (needed <= *capacity) {
        return 0;
    }
    size_t wanted = *capacity < 16 ? 16 : *capacity;
    while (wanted < needed) {
        if (wanted > SIZE_MAX / 2) {
            return refuse(r, "out of memory");
        }
        wanted *= 2;
    }
    if (wanted > SIZE_MAX / size) {
        return refuse(r, "out of memory");
    }
    void *grown = realloc(*array, wanted * size);
    if (grown == NULL) {
        return refuse(r, "out of memory");
    }
    *array = grown;
    *capacity = wanted;
    return 0;
}

static plan_value *push_value(reader *r)
{
    ssx_plan *p = r->plan;
    if (reserve(r, (void **)&p->values, &r->values_capacity, p->n_values_total + 1,
                sizeof *p->values) != 0) {
        return NULL;
    }
    plan_value *value = &p->values[p->n_values_total++];
    memset(value, 0, sizeof *value);
    return value;
}

/* ------------------------------------------------------------------ tokens */
static int is_blank(char c)
{
    return c == ' ' || c == '\t';
}

/* The next bare token of the line into [*start, *start + *size); 0 when the line has no more
 * (its end or a comment). */
static int next_token(reader *r, const char **start, size_t *size)
{
    while (r->at < r->end && is_blank(*r->at)) {
        ++r->at;
    }
    if (r->at == r->end || *r->at == '#') {
        return 0;
    }
    *start = r->at;
    while (r->at < r->end && !is_blank(*r->at)) {
        ++r->at;
    }
    *size = (size_t)(r->at - *start);
    return 1;
}

static int hex_digit(char c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    return -1;
}

/* A quoted string at r->at (its opening quote), decoded into the pool. */
static int read_string(reader *r, plan_value *value, int allow_nul)
{
    ssx_plan *p = r->plan;
    size_t offset = p->pool_size;
    const char *s = r->at + 1;
    for (;;) {
        if (s >= r->end) {
            return refuse(r, "the string has no closing quote");
        }
        char c = *s++;
        if (c == '"') {
            break;
        }
        if (c == '\\') {
            if (s >= r->end) {
                return refuse(r, "the string ends inside an escape");
            }
            char e = *s++;
            if (e == 'n') {
                c = '\n';
            } else if (e == 't') {
                c = '\t';
            } else if (e == '"' || e == '\\') {
                c = e;
            } else if (e == 'x') {
                int high = s < r->end ? hex_digit(s[0]) : -1;
                int low = s + 1 < r->end ? hex_digit(s[1]) : -1;
                if (high < 0 || low < 0) {
                    return refuse(r, "\\x needs two hex digits");
                }
                c = (char)(high * 16 + low);
                s += 2;
            } else {
                return refuse(r, "unknown escape \\%c", e);
            }
        }
        if (c == '\0' && !allow_nul) {
            return refuse(r, "a name or path may not hold a NUL byte");
        }
        if (p->pool_size - offset >= PLAN_MAX_STRING) {
            return refuse(r, "the string is longer than %d bytes", PLAN_MAX_STRING);
        }
        if (reserve(r, (void **)&p->pool, &r->pool_capacity, p->pool_size + 2, 1) != 0) {
            return -1;
        }
        p->pool[p->pool_size++] = c;
    }
    if (s < r->end && !is_blank(*s)) {
        return refuse(r, "the string's closing quote is not followed by a space");
    }
    if (reserve(r, (void **)&p->pool, &r->pool_capacity, p->pool_size + 1, 1) != 0) {
        return -1;
    }
    p->pool[p->pool_size++] = '\0';
    r->at = s;
    value->kind = PLAN_STRING;
    value->as.text.offset = offset;
    value->as.text.size = p->pool_size - 1 - offset;
    return 0;
}

static int copy_number(reader *r, const char *start, size_t size, char *out)
{
    if (size >= PLAN_MAX_NUMBER) {
        return refuse(r, "'%.20s...' is too long for a number", start);
    }
    memcpy(out, start, size);
    out[size] = '\0';
    return 0;
}

static int parse_integer(reader *r, const char *start, size_t size, int64_t low, int64_t high,
                         int64_t *out)
{
    char text[PLAN_MAX_NUMBER];
    if (copy_number(r, start, size, text) != 0) {
        return -1;
    }
    char *stop = NULL;
    errno = 0;
    long long value = strtoll(text, &stop, 10);
    if (stop == text || *stop != '\0' || (size_t)(stop - text) != size) {
        return refuse(r, "'%s' is not an integer", text);
    }
    if (errno == ERANGE || value < low || value > high) {
        return refuse(r, "%s is outside %lld..%lld", text, (long long)low, (long long)high);
    }
    *out = (int64_t)value;
    return 0;
}

static int parse_double(reader *r, const char *start, size_t size, double *out)
{
    char text[PLAN_MAX_NUMBER];
    if (copy_number(r, start, size, text) != 0) {
        return -1;
    }
    char *stop = NULL;
    double value = strtod(text, &stop);
    if (stop == text || *stop != '\0' || (size_t)(stop - text) != size) {
        return refuse(r, "'%s' is not a number", text);
    }
    *out = value;
    return 0;
}

/* ------------------------------------------------------------------ fields */
static int missing(reader *r)
{
    return refuse(r, "missing");
}

static int read_integer(reader *r, int64_t low, int64_t high, int64_t *out)
{
    const char *start = NULL;
    size_t size = 0;
    if (!next_token(r, &start, &size)) {
        return missing(r);
    }
    int64_t value = 0;
    if (parse_integer(r, start, size, low, high, &value) != 0) {
        return -1;
    }
    plan_value *v = push_value(r);
    if (v == NULL) {
        return -1;
    }
    v->kind = PLAN_INTEGER;
    v->as.integer = value;
    if (out != NULL) {
        *out = value;
    }
    return 0;
}

static int read_word(reader *r, plan_word_set set)
{
    const char *start = NULL;
    size_t size = 0;
    if (!next_token(r, &start, &size)) {
        return missing(r);
    }
    const char *const *words = plan_words(set);
    for (int k = 0; words[k] != NULL; ++k) {
        if (strlen(words[k]) == size && memcmp(words[k], start, size) == 0) {
            plan_value *v = push_value(r);
            if (v == NULL) {
                return -1;
            }
            v->kind = PLAN_WORD;
            v->word_set = (uint8_t)set;
            v->as.integer = k;
            return 0;
        }
    }
    char choices[256] = "";
    for (int k = 0; words[k] != NULL; ++k) {
        size_t used = strlen(choices);
        snprintf(choices + used, sizeof choices - used, "%s%s", k ? ", " : "", words[k]);
    }
    return refuse(r, "'%.*s' is none of %s", (int)(size < 40 ? size : 40), start, choices);
}

/* A string ("s", allow_nul 0; "v" allows any byte), or with `number_too` a number instead. */
static int read_string_or_number(reader *r, int number_too, int allow_nul)
{
    while (r->at < r->end && is_blank(*r->at)) {
        ++r->at;
    }
    if (r->at == r->end || *r->at == '#') {
        return missing(r);
    }
    plan_value *v = push_value(r);
    if (v == NULL) {
        return -1;
    }
    if (*r->at == '"') {
        return read_string(r, v, allow_nul);
    }
    if (!number_too) {
        return refuse(r, "a string is written in double quotes");
    }
    const char *start = NULL;
    size_t size = 0;
    next_token(r, &start, &size);
    v->kind = PLAN_DOUBLE;
    return parse_double(r, start, size, &v->as.real);
}

static int read_double(reader *r)
{
    const char *start = NULL;
    size_t size = 0;
    if (!next_token(r, &start, &size)) {
        return missing(r);
    }
    plan_value *v = push_value(r);
    if (v == NULL) {
        return -1;
    }
    v->kind = PLAN_DOUBLE;
    return parse_double(r, start, size, &v->as.real);
}

/* A lowercase hex digit's value plus one, 0 for any other byte: one look-up a digit. */
static const unsigned char lowercase_hex_plus_one[256] = {
    ['0'] = 1, ['1'] = 2, ['2'] = 3, ['3'] = 4, ['4'] = 5, ['5'] = 6, ['6'] = 7, ['7'] = 8,
    ['8'] = 9, ['9'] = 10, ['a'] = 11, ['b'] = 12, ['c'] = 13, ['d'] = 14, ['e'] = 15,
    ['f'] = 16,
};

/* A list of doubles in its hex form, the token [start, start + size): `x`, the count, `:`,
 * then each value's IEEE-754 binary64 bytes, least significant first, as 16 lowercase hex
 * digits. Pushed as the decimal form is: the count, then the values. The digits are checked
 * against the count before anything is stored. */
static int read_hex_doubles(reader *r, const char *start, size_t size)
{
    const char *colon = memchr(start, ':', size);
    if (colon == NULL) {
        return refuse(r, "a hex list is x, its count, ':' and its digits; '%.*s' has no ':'",
                      (int)(size < 20 ? size : 20), start);
    }
    int64_t count = 0;
    if (parse_integer(r, start + 1, (size_t)(colon - start) - 1, 0, PLAN_MAX_LIST, &count) !=
        0) {
        return -1;
    }
    const char *digits = colon + 1;
    size_t n_digits = size - (size_t)(digits - start);
    if (n_digits % 2 != 0) {
        return refuse(r, "the hex list has an odd number of digits (%zu)", n_digits);
    }
    if (n_digits % 16 != 0 || n_digits / 16 != (uint64_t)count) {
        return refuse(r, "the hex list holds %zu digits for %lld values (16 a value)",
                      n_digits, (long long)count);
    }
    ssx_plan *p = r->plan;
    if (reserve(r, (void **)&p->values, &r->values_capacity,
                p->n_values_total + 1 + (size_t)count, sizeof *p->values) != 0) {
        return -1;
    }
    plan_value *v = push_value(r);
    if (v == NULL) {
        return -1;
    }
    v->kind = PLAN_INTEGER;
    v->as.integer = count;
    long outer = r->item;
    for (int64_t k = 0; k < count; ++k) {
        const unsigned char *value = (const unsigned char *)digits + 16 * k;
        uint64_t bits = 0;
        unsigned int valid = 1;
        for (int byte = 0; byte < 8; ++byte) {
            unsigned int high = lowercase_hex_plus_one[value[2 * byte]];
            unsigned int low = lowercase_hex_plus_one[value[2 * byte + 1]];
            valid &= high != 0 && low != 0;
            bits |= (uint64_t)(((high - 1) << 4 | (low - 1)) & 0xffu) << (8 * byte);
        }
        if (!valid) {
            size_t at = 0;
            while (lowercase_hex_plus_one[value[at]] != 0) {
                ++at;
            }
            r->item = (long)k;
            return value[at] > 0x20 && value[at] < 0x7f
                   ? refuse(r, "'%c' is not a lowercase hex digit", value[at])
                   : refuse(r, "byte 0x%02x is not a lowercase hex digit", value[at]);
        }
        v = push_value(r);
        if (v == NULL) {
            return -1;
        }
        v->kind = PLAN_DOUBLE;
        memcpy(&v->as.real, &bits, sizeof bits);
    }
    r->item = outer;
    return 0;
}

/* The index of the last component read must have more than `index` ports of `counts`. */
static int check_port(reader *r, const int *counts, int64_t index, const char *what)
{
    int c = r->last_component;
    if (c < 0) {
        return refuse(r, "no component named before the %s", what);
    }
    if (index >= counts[c]) {
        return refuse(r, "component %d has no %s %lld (it has %d)", c, what, (long long)index,
                      counts[c]);
    }
    return 0;
}

static int read_signature(reader *r, const char *signature, size_t length, int top_level);

static int read_element(reader *r, const char *e, size_t *used)
{
    ssx_plan *p = r->plan;
    int64_t value = 0;
    *used = 1;
    switch (*e) {
    case 'c':
        if (read_integer(r, 0, INT_MAX, &value) != 0) {
            return -1;
        }
        if (value >= p->n_components) {
            return refuse(r, "no component %lld defined before (there are %d)",
                          (long long)value, p->n_components);
        }
        r->last_component = (int)value;
        return 0;
    case 'o':
        return read_integer(r, 0, INT_MAX, &value) != 0 ? -1
               : check_port(r, p->n_outputs, value, "output");
    case 'n':
        return read_integer(r, 0, INT_MAX, &value) != 0 ? -1
               : check_port(r, p->n_inputs, value, "input");
    case 'x':
        if (read_integer(r, 0, INT_MAX, &value) != 0) {
            return -1;
        }
        return value < p->n_indicators ? 0
               : refuse(r, "no indicator %lld defined before (there are %d)", (long long)value,
                        p->n_indicators);
    case 'i':
        return read_integer(r, INT_MIN, INT_MAX, NULL);
    case 'z':
        return read_integer(r, 0, (int64_t)1 << 53, NULL);
    case 'u':
        return read_integer(r, 0, UINT_MAX, NULL);
    case 'f':
        return read_integer(r, 0, 1, NULL);
    case 'D':
        return read_integer(r, -1, 1, NULL);
    case 'V':
        return read_integer(r, 1, 3, NULL);
    case 'd':
        return read_double(r);
    case 's':
        return read_string_or_number(r, 0, 0);
    case 'v':
        return read_string_or_number(r, 1, 1);
    case 'T':
        return read_word(r, PLAN_WORDS_VALUE_TYPE);
    case '3':
        return read_word(r, PLAN_WORDS_FMI3_TYPE);
    case 'K':
        return read_word(r, PLAN_WORDS_SOURCE);
    case 'G':
        return read_word(r, PLAN_WORDS_COUPLING);
    case 'J':
        return read_word(r, PLAN_WORDS_JACOBIAN);
    case 'L':
        return read_word(r, PLAN_WORDS_LOCATOR);
    case 'g':
        if (read_integer(r, 0, PLAN_MAX_COMPONENTS, &value) != 0 ||
            read_integer(r, 0, 1, NULL) != 0) {
            return -1;
        }
        for (int64_t k = 0; k < value; ++k) {
            size_t one;
            if (read_element(r, "c", &one) != 0) {
                return -1;
            }
        }
        return 0;
    case '[': {
        const char *close = strchr(e, ']');
        *used = (size_t)(close - e) + 1;
        const char *start = NULL;
        size_t size = 0;
        const char *before = r->at;
        if (close == e + 2 && e[1] == 'd' && next_token(r, &start, &size) && *start == 'x') {
            return read_hex_doubles(r, start, size);
        }
        r->at = before; /* the count of a list in its decimal form */
        if (read_integer(r, 0, PLAN_MAX_LIST, &value) != 0) {
            return -1;
        }
        long outer = r->item;
        for (int64_t k = 0; k < value; ++k) {
            r->item = (long)k;
            if (read_signature(r, e + 1, (size_t)(close - e) - 1, 0) != 0) {
                return -1;
            }
        }
        r->item = outer;
        return 0;
    }
    default:
        return refuse(r, "the schema has no letter '%c'", *e);
    }
}

static int read_signature(reader *r, const char *signature, size_t length, int top_level)
{
    size_t k = 0;
    while (k < length) {
        size_t used;
        if (read_element(r, signature + k, &used) != 0) {
            return -1;
        }
        k += used;
        if (top_level) {
            ++r->field;
        }
    }
    return 0;
}

/* ------------------------------------------------------------------ what records define */
static const plan_value *value_of(const reader *r, size_t k)
{
    ssx_plan *p = r->plan;
    return &p->values[p->first_value[p->n_records - 1] + k];
}

static int add_component(reader *r, int64_t table_rows, int fmi_version)
{
    ssx_plan *p = r->plan;
    if (p->n_components >= PLAN_MAX_COMPONENTS) {
        return refuse(r, "more than %d components", PLAN_MAX_COMPONENTS);
    }
    size_t n = (size_t)p->n_components + 1, capacity = r->components_capacity;
    if (reserve(r, (void **)&p->component_record, &capacity, n, sizeof(size_t)) != 0) {
        return -1;
    }
    capacity = r->components_capacity;
    if (reserve(r, (void **)&p->n_outputs, &capacity, n, sizeof(int)) != 0) {
        return -1;
    }
    capacity = r->components_capacity;
    if (reserve(r, (void **)&p->n_inputs, &capacity, n, sizeof(int)) != 0) {
        return -1;
    }
    capacity = r->components_capacity;
    if (reserve(r, (void **)&r->table_rows, &capacity, n, sizeof(int64_t)) != 0) {
        return -1;
    }
    capacity = r->components_capacity;
    if (reserve(r, (void **)&r->fmi_version, &capacity, n, sizeof(int)) != 0) {
        return -1;
    }
    r->components_capacity = capacity;
    int c = p->n_components++;
    p->component_record[c] = p->n_records - 1;
    p->n_outputs[c] = 0;
    p->n_inputs[c] = 0;
    r->table_rows[c] = table_rows;
    r->fmi_version[c] = fmi_version;
    return 0;
}

static int count_port(reader *r, int *counts, int c)
{
    if (counts[c] == INT_MAX) {
        return refuse(r, "too many ports");
    }
    ++counts[c];
    return 0;
}

static int needs_fmu(reader *r, int c, int version)
{
    r->field = 0;
    if (r->fmi_version[c] == 0) {
        return refuse(r, "component %d is not an FMU", c);
    }
    if (version != 0 && r->fmi_version[c] != version) {
        return refuse(r, "component %d is an FMI %d.0 FMU, not FMI %d.0", c, r->fmi_version[c],
                      version);
    }
    return 0;
}

/* A start value of `type` (a word of value types) as `value` holds it. */
static int check_start(reader *r, int64_t type, const plan_value *value, int nan_allowed)
{
    int text = type == SSX_STRING || type == SSX_BINARY;
    if (text) {
        if (value->kind != PLAN_STRING && !(nan_allowed && value->as.real != value->as.real)) {
            return refuse(r, "a %s value is a string", plan_words(PLAN_WORDS_VALUE_TYPE)[type]);
        }
        return 0;
    }
    if (value->kind != PLAN_DOUBLE) {
        return refuse(r, "a %s value is a number", plan_words(PLAN_WORDS_VALUE_TYPE)[type]);
    }
    double v = value->as.real;
    if (nan_allowed && v != v) {
        return 0;
    }
    if (type == SSX_BOOLEAN && v != 0.0 && v != 1.0) {
        return refuse(r, "a boolean value is 0 or 1, not %.17g", v);
    }
    if (type == SSX_INTEGER && !(v >= INT_MIN && v <= INT_MAX && v == (double)(long long)v)) {
        return refuse(r, "%.17g is not an integer of the engine's range", v);
    }
    return 0;
}

/* How many event sources of `kind` (ssx_event_source_kind) the records so far define. */
static int64_t sources_defined(const ssx_plan *p, int64_t kind)
{
    if (kind == SSX_SOURCE_OWN_EVENTS) {
        return p->n_components;
    }
    if (kind == SSX_SOURCE_INDICATOR) {
        return p->n_indicators;
    }
    int64_t clocks = 0;
    for (size_t k = 0; k < p->n_records; ++k) {
        clocks += p->kind[k] == PLAN_OUTPUT_CLOCK_SOURCE;
    }
    return clocks;
}

static int define(reader *r, int kind)
{
    ssx_plan *p = r->plan;
    int c = (int)value_of(r, 0)->as.integer; /* the component of records that name one */
    switch (kind) {
    case PLAN_SYSTEM:
        if (p->n_records != 1) {
            return refuse(r, "the system is named once, by the first record");
        }
        return 0;
    case PLAN_EXPERIMENT:
        for (size_t k = 0; k + 1 < p->n_records; ++k) {
            if (p->kind[k] == PLAN_EXPERIMENT) {
                return refuse(r, "a second experiment (the first on line %zu)", p->line[k]);
            }
        }
        return 0;
    case PLAN_FMU:
        return add_component(r, -1, (int)value_of(r, 2)->as.integer);
    case PLAN_MODEL_EXCHANGE:
        return add_component(r, -1, (int)value_of(r, 4)->as.integer);
    case PLAN_TABLE:
        return add_component(r, value_of(r, 1)->as.integer, 0);
    case PLAN_PYTHON:
        return add_component(r, -1, 0);
    case PLAN_SCHEDULED_EXECUTION:
        return add_component(r, -1, 3);
    case PLAN_SCHEDULED_CLOCK:
    case PLAN_SCHEDULED_CLOCK_OUTPUT:
        return needs_fmu(r, c, 3);
    case PLAN_TABLE_COLUMN:
        if (r->table_rows[c] < 0) {
            r->field = 0;
            return refuse(r, "component %d is not a table", c);
        }
        if (value_of(r, 3)->as.integer != r->table_rows[c]) {
            r->field = 3;
            return refuse(r, "%lld values for a table of %lld rows",
                          (long long)value_of(r, 3)->as.integer, (long long)r->table_rows[c]);
        }
        return count_port(r, p->n_outputs, c);
    case PLAN_FMU_EXPERIMENT:
    case PLAN_ISOLATED:
    case PLAN_RESTART_HANDLER:
        return needs_fmu(r, c, 0);
    case PLAN_START:
        if (needs_fmu(r, c, 0) != 0) {
            return -1;
        }
        r->field = 3;
        return check_start(r, value_of(r, 1)->as.integer, value_of(r, 3), 0);
    case PLAN_FMI3_VARIABLES:
    case PLAN_FMI3_VARIABLE:
    case PLAN_FMI3_ELEMENT:
    case PLAN_FMI3_INTERMEDIATE:
    case PLAN_FMI3_CLOCK:
    case PLAN_FMI3_TRIGGERED_CLOCK:
    case PLAN_FMI3_OUTPUT_CLOCK:
    case PLAN_FMI3_COUNTDOWN_CLOCK:
    case PLAN_FMI3_CHANGING_CLOCK:
        return needs_fmu(r, c, 3);
    case PLAN_OUTPUT:
        return count_port(r, p->n_outputs, c);
    case PLAN_INPUT:
        r->field = 3;
        if (check_start(r, value_of(r, 1)->as.integer, value_of(r, 3), 1) != 0) {
            return -1;
        }
        return count_port(r, p->n_inputs, c);
    case PLAN_INDICATOR_OUTPUT:
    case PLAN_INDICATOR_CALLBACK:
        if (p->n_indicators == INT_MAX) {
            return refuse(r, "too many indicators");
        }
        ++p->n_indicators;
        return 0;
    case PLAN_SUBSCRIBE:
    case PLAN_CONNECT_CLOCK: {
        static const char *const what[] = {"indicator", "component", "output clock source"};
        int64_t kind = value_of(r, 0)->as.integer;
        int64_t index = value_of(r, 1)->as.integer;
        if (index >= sources_defined(p, kind)) {
            r->field = 1;
            return refuse(r, "no %s %lld defined before", what[kind], (long long)index);
        }
        return 0;
    }
    default:
        return 0;
    }
}

/* ------------------------------------------------------------------ lines */
static int read_record(reader *r)
{
    ssx_plan *p = r->plan;
    const char *start = NULL;
    size_t size = 0;
    next_token(r, &start, &size); /* the caller saw a token */
    if (*start == '"') {
        return refuse(r, "a record starts with its keyword, not a string");
    }
    int kind = plan_record_kind_of(start, size);
    if (kind < 0) {
        return refuse(r, "unknown keyword '%.*s'", (int)(size < 40 ? size : 40), start);
    }
    if (p->n_records == 0 && kind != PLAN_SYSTEM) {
        return refuse(r, "the first record is 'system', not '%s'", plan_schema[kind].keyword);
    }
    size_t capacity = r->records_capacity, n = p->n_records + 1;
    if (reserve(r, (void **)&p->kind, &capacity, n, sizeof *p->kind) != 0) {
        return -1;
    }
    capacity = r->records_capacity;
    if (reserve(r, (void **)&p->line, &capacity, n, sizeof *p->line) != 0) {
        return -1;
    }
    capacity = r->records_capacity;
    if (reserve(r, (void **)&p->first_value, &capacity, n, sizeof *p->first_value) != 0) {
        return -1;
    }
    capacity = r->records_capacity;
    if (reserve(r, (void **)&p->n_values, &capacity, n, sizeof *p->n_values) != 0) {
        return -1;
    }
    r->records_capacity = capacity;
    size_t record = p->n_records++;
    p->kind[record] = (uint8_t)kind;
    p->line[record] = r->line;
    p->first_value[record] = p->n_values_total;
    r->record = kind;
    r->field = 0;
    r->item = -1;
    r->last_component = -1;
    const char *signature = plan_schema[kind].signature;
    if (read_signature(r, signature, strlen(signature), 1) != 0) {
        return -1;
    }
    p->n_values[record] = p->n_values_total - p->first_value[record];
    if (next_token(r, &start, &size)) {
        r->field = -1;
        return refuse(r, "more fields than the record takes");
    }
    r->field = -1;
    return define(r, kind);
}

static void reader_free(reader *r)
{
    free(r->table_rows);
    free(r->fmi_version);
}

ssx_plan *ssx_plan_read(const char *text, size_t size, char *error, size_t error_size)
{
    reader r = {.error = error, .error_size = error_size, .record = -1, .field = -1,
                .item = -1, .last_component = -1};
    if (error != NULL && error_size > 0) {
        error[0] = '\0';
    }
    if (text == NULL && size > 0) {
        refuse(&r, "no text");
        return NULL;
    }
    if (size > PLAN_MAX_TEXT) {
        refuse(&r, "the plan is larger than %zu bytes", PLAN_MAX_TEXT);
        return NULL;
    }
    r.plan = calloc(1, sizeof *r.plan);
    if (r.plan == NULL || reserve(&r, (void **)&r.plan->pool, &r.pool_capacity, 1, 1) != 0) {
        refuse(&r, "out of memory");
        ssx_plan_free(r.plan);
        return NULL;
    }
    size_t pos = 0;
    while (pos < size) {
        ++r.line;
        const char *line = text + pos;
        const char *newline = memchr(line, '\n', size - pos);
        size_t length = newline != NULL ? (size_t)(newline - line) : size - pos;
        pos += length + (newline != NULL);
        if (length > PLAN_MAX_LINE) {
            refuse(&r, "the line is longer than %d bytes", PLAN_MAX_LINE);
            break;
        }
        if (length > 0 && line[length - 1] == '\r') {
            --length;
        }
        r.at = line;
        r.end = line + length;
        r.record = -1;
        r.field = -1;
        if (r.line == 1) {
            if (length != strlen(PLAN_HEADER) || memcmp(line, PLAN_HEADER, length) != 0) {
                refuse(&r, "a plan starts with the line '" PLAN_HEADER "'");
                break;
            }
            continue;
        }
        const char *start = NULL;
        size_t token_size = 0;
        if (!next_token(&r, &start, &token_size)) {
            continue; /* blank or a comment */
        }
        r.at = start;
        if (read_record(&r) != 0) {
            break;
        }
    }
    if (!r.failed && r.line == 0) {
        r.line = 1;
        refuse(&r, "a plan starts with the line '" PLAN_HEADER "'");
    } else if (!r.failed && r.plan->n_records == 0) {
        r.record = -1;
        refuse(&r, "the plan has no 'system' record");
    }
    reader_free(&r);
    if (r.failed) {
        ssx_plan_free(r.plan);
        return NULL;
    }
    return r.plan;
}

void ssx_plan_free(ssx_plan *plan)
{
    if (plan == NULL) {
        return;
    }
    free(plan->kind);
    free(plan->line);
    free(plan->first_value);
    free(plan->n_values);
    free(plan->values);
    free(plan->pool);
    free(plan->component_record);
    free(plan->n_outputs);
    free(plan->n_inputs);
    free(plan);
}
