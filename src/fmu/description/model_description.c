/* modelDescription.xml of FMI 2.0 and FMI 1.0 into compact arrays (the contract is in
 * syssimx_engine.h): the FMI model layer over the XML tokenizer (xml_tokenizer.c), its texts
 * kept in the string store (string_store.c). FMI 1.0's variables are told in FMI 2.0's words
 * (see fmi1_words).
 *
 * Read top-down: the API, the model layer (which elements count where, the checks of a
 * variable), the values, the errors, then the arrays handed to the ssx_md.
 */
#include "syssimx_engine.h"

#include "array.h"
#include "string_store.h"
#include "xml_tokenizer.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* FMI 2.0, section 2.2.7: the initial a variable has when it declares none, by variability
 * (rows) and causality (columns); INVALID marks a combination the standard forbids. */
enum { INVALID = 0xFF };
static const uint8_t INITIAL_DEFAULT[5][6] = {
    /* columns: parameter, calculatedParameter, input, output, local, independent */
    /* constant */ {INVALID, INVALID, INVALID, SSX_MD_EXACT, SSX_MD_EXACT, INVALID},
    /* fixed */ {SSX_MD_EXACT, SSX_MD_CALCULATED, INVALID, INVALID, SSX_MD_CALCULATED, INVALID},
    /* tunable */ {SSX_MD_EXACT, SSX_MD_CALCULATED, INVALID, INVALID, SSX_MD_CALCULATED, INVALID},
    /* discrete */ {INVALID, INVALID, SSX_MD_EXACT, SSX_MD_CALCULATED, SSX_MD_CALCULATED, INVALID},
    /* continuous */ {INVALID, INVALID, SSX_MD_EXACT, SSX_MD_CALCULATED, SSX_MD_CALCULATED,
                      SSX_MD_NONE},
};

#define WORD(text) {text, sizeof text - 1}
static const struct {
    const char *text;
    size_t length;
} WORDS[SSX_MD_WORD_COUNT] = {
    WORD(""), WORD("parameter"), WORD("calculatedParameter"), WORD("input"), WORD("output"),
    WORD("local"), WORD("independent"), WORD("constant"), WORD("fixed"), WORD("tunable"),
    WORD("discrete"), WORD("continuous"), WORD("exact"), WORD("approx"), WORD("calculated"),
    WORD("Real"), WORD("Integer"), WORD("Boolean"), WORD("String"), WORD("Enumeration"),
};
#undef WORD

/* The ScalarVariable being read: its attributes, then those of its type element. */
typedef struct {
    bool open;
    size_t line;
    slice name, value_reference, causality, variability, initial, description;
    slice alias; /* FMI 1.0 */
    int type; /* SSX_MD_NONE until the type element */
    slice start, unit, declared_type;
    slice derivative; /* of a Real: the index (from 1) of the variable it is the derivative of */
} variable_parts;

typedef struct {
    ssx_md *md;
    xml_tokenizer xml;
    /* the model layer */
    bool fmi_root;
    bool fmi1; /* the root declares fmiVersion 1.0 */
    slice section, subsection; /* the open elements at depth 2 and 3 */
    variable_parts variable;
    bool in_type, type_has_element;
    size_t type_line;
    slice type_name, type_description;
    ssx_md_names type_index;
    /* the storage */
    string_pool strings;
    ssx_md_attribute *kept;
    size_t kept_count, kept_capacity;
    ssx_md_simple_type *types;
    size_t type_count, type_capacity;
    size_t count, capacity; /* variables */
    uint32_t *name, *value_reference, *description, *unit, *start, *derivative;
    int32_t *declared_type;
    uint8_t *type, *causality, *variability, *initial;
    size_t output_count, output_capacity, dependency_total, dependency_capacity;
    uint32_t *output, *dependencies;
    size_t *first_dependency;
    int64_t *dependency_count;
    size_t derivative_count;
    size_t duplicate_count;
    ssx_md_names *names;
} reader;

static bool start_element(void *user, slice tag, size_t line);
static bool end_element(void *user);
static bool finish_variable(reader *r);
static bool finish_type(reader *r);
static bool read_unknown(reader *r, size_t line);
static bool read_derivative(reader *r, const variable_parts *v, uint32_t *derivative);
static bool push_output(reader *r, uint32_t index);
static bool keep_attributes(reader *r, slice tag);
static bool store(reader *r, slice text, uint32_t *offset);
static bool view(reader *r, slice value, slice *text);
static bool grow_variables(reader *r);
static bool parse_integer(const char *text, size_t length, int64_t *value);
static bool is_start_of(int type, const char *text, size_t length);
static bool fail(reader *r, ssx_md_problem problem, size_t line, const char *subject, slice text,
                 slice other);
static bool out_of_memory(reader *r);
static void publish(reader *r);

static bool is_word(slice s, int word)
{
    return s.length == WORDS[word].length && memcmp(s.at, WORDS[word].text, s.length) == 0;
}

/* ------------------------------------------------------------------------------ the API */
ssx_md *ssx_md_read(const char *xml, size_t size)
{
    ssx_md *md = calloc(1, sizeof *md);
    if (md == NULL) {
        return NULL;
    }
    if (size >= UINT32_MAX) { /* the pool's offsets are 32 bits */
        md->error.problem = SSX_MD_TOO_LARGE;
        return md;
    }
    reader r = {.md = md};
    r.xml = (xml_tokenizer){.at = xml, .end = xml + size, .line = 1, .error = &md->error,
                            .handler = {start_element, end_element}, .user = &r};
    r.names = calloc(1, sizeof *r.names);
    /* about what a large model's texts take */
    if (r.names == NULL || !string_pool_start(&r.strings, 1 + size / 4)) {
        out_of_memory(&r);
    } else if (xml_read_document(&r.xml) && !r.fmi_root) {
        fail(&r, SSX_MD_NO_FMI_ROOT, 1, NULL, (slice){0}, (slice){0});
    }
    publish(&r);
    return md;
}

int64_t ssx_md_find(const ssx_md *md, const char *name)
{
    return name_index_find(md->names, md->strings, name);
}

const char *ssx_md_word_text(int word)
{
    return word >= 0 && word < SSX_MD_WORD_COUNT ? WORDS[word].text : "";
}

size_t ssx_md_join(const ssx_md *md, const uint32_t *offsets, size_t n, char *out,
                   size_t out_size)
{
    size_t size = 0;
    for (size_t i = 0; i < n; ++i) {
        const char *text = md->strings + offsets[i];
        size_t length = strlen(text) + (i + 1 < n); /* the separator */
        if (length > 0 && size + length <= out_size) { /* out may be NULL when it sizes */
            memcpy(out + size, text, length); /* the NUL of the text separates it */
        }
        size += length;
    }
    return size;
}

void ssx_md_free(ssx_md *md)
{
    if (md == NULL) {
        return;
    }
    /* The arrays are const for the reader's users only; they were allocated by publish(). */
    free((void *)md->strings);
    free((void *)md->attributes);
    free((void *)md->types);
    free((void *)md->name);
    free((void *)md->value_reference);
    free((void *)md->description);
    free((void *)md->unit);
    free((void *)md->start);
    free((void *)md->declared_type);
    free((void *)md->derivative);
    free((void *)md->type);
    free((void *)md->causality);
    free((void *)md->variability);
    free((void *)md->initial);
    free((void *)md->output);
    free((void *)md->first_dependency);
    free((void *)md->dependency_count);
    free((void *)md->dependencies);
    name_index_free(md->names);
    free(md->names);
    free(md->error.subject);
    free(md->error.text);
    free(md->error.other);
    free(md);
}

/* ------------------------------------------------------------------------------ the model */
static bool start_element(void *user, slice tag, size_t line)
{
    reader *r = user;
    switch (r->xml.depth) {
    case 1:
        if (!slice_is(tag, "fmiModelDescription")) {
            return true;
        }
        r->fmi_root = true;
        if (!keep_attributes(r, tag)) {
            return false;
        }
        for (size_t i = 0; i < r->xml.attribute_count; ++i) {
            if (slice_is(r->xml.attributes[i].name, "fmiVersion")) {
                slice version;
                if (!view(r, r->xml.attributes[i].value, &version)) {
                    return false;
                }
                r->fmi1 = slice_is(version, "1.0");
                return slice_is(version, "2.0") || r->fmi1
                           ? true
                           : fail(r, SSX_MD_NOT_FMI2, line, NULL, version, (slice){0});
            }
        }
        /* before reading variables of another schema */
        return fail(r, SSX_MD_NOT_FMI2, line, NULL, (slice){0}, (slice){0});
    case 2:
        r->section = tag;
        if (slice_is(tag, "CoSimulation") || slice_is(tag, "ModelExchange") ||
            slice_is(tag, "DefaultExperiment")) {
            return keep_attributes(r, tag);
        }
        return true;
    case 3:
        r->subsection = tag;
        if (slice_is(tag, "ScalarVariable") && slice_is(r->section, "ModelVariables")) {
            variable_parts *v = &r->variable;
            *v = (variable_parts){.open = true, .line = line};
            for (size_t i = 0; i < r->xml.attribute_count; ++i) {
                slice name = r->xml.attributes[i].name, value = r->xml.attributes[i].value;
                if (slice_is(name, "name")) {
                    v->name = value;
                } else if (slice_is(name, "valueReference")) {
                    v->value_reference = value;
                } else if (slice_is(name, "causality")) {
                    v->causality = value;
                } else if (slice_is(name, "variability")) {
                    v->variability = value;
                } else if (slice_is(name, "initial")) {
                    v->initial = value;
                } else if (slice_is(name, "description")) {
                    v->description = value;
                } else if (slice_is(name, "alias")) {
                    v->alias = value;
                }
            }
        } else if (slice_is(tag, r->fmi1 ? "Type" : "SimpleType") &&
                   slice_is(r->section, "TypeDefinitions")) {
            r->in_type = true;
            r->type_has_element = false;
            r->type_line = line;
            r->type_name = r->type_description = (slice){0};
            for (size_t i = 0; i < r->xml.attribute_count; ++i) {
                if (slice_is(r->xml.attributes[i].name, "name")) {
                    r->type_name = r->xml.attributes[i].value;
                } else if (slice_is(r->xml.attributes[i].name, "description")) {
                    r->type_description = r->xml.attributes[i].value;
                }
            }
        }
        return true;
    case 4:
        if (r->variable.open) {
            variable_parts *v = &r->variable;
            if (v->type != SSX_MD_NONE) {
                return true; /* the first type element counts */
            }
            for (int word = SSX_MD_REAL; word <= SSX_MD_ENUMERATION; ++word) {
                if (is_word(tag, word)) {
                    v->type = word;
                }
            }
            for (size_t i = 0; v->type != SSX_MD_NONE && i < r->xml.attribute_count; ++i) {
                slice name = r->xml.attributes[i].name, value = r->xml.attributes[i].value;
                if (slice_is(name, "start")) {
                    v->start = value;
                } else if (slice_is(name, "unit")) {
                    v->unit = value;
                } else if (slice_is(name, "declaredType")) {
                    v->declared_type = value;
                } else if (slice_is(name, "derivative")) {
                    v->derivative = value;
                }
            }
            return true;
        }
        if (r->in_type) {
            return r->type_has_element ? true : finish_type(r);
        }
        if (r->fmi1 && slice_is(tag, "Capabilities") && slice_is(r->section, "Implementation")) {
            return keep_attributes(r, tag); /* of CoSimulation_StandAlone or _Tool */
        }
        if (slice_is(tag, "Unknown") && slice_is(r->subsection, "Outputs") &&
            slice_is(r->section, "ModelStructure")) {
            return read_unknown(r, line); /* syssimx reads the feedthrough of outputs only */
        }
        if (slice_is(tag, "Unknown") && slice_is(r->subsection, "Derivatives") &&
            slice_is(r->section, "ModelStructure")) {
            ++r->derivative_count; /* a Model Exchange FMU's number of continuous states */
        }
        return true;
    default:
        return true;
    }
}

/* The tokenizer has closed the element: `depth` elements remain open. */
static bool end_element(void *user)
{
    reader *r = user;
    if (r->xml.depth != 2) {
        return true;
    }
    if (r->variable.open) {
        r->variable.open = false;
        return finish_variable(r);
    }
    if (r->in_type) {
        r->in_type = false;
        if (!r->type_has_element) {
            char *name = NULL;
            if (r->type_name.at != NULL) {
                uint32_t offset;
                if (!store(r, r->type_name, &offset)) {
                    return false;
                }
                name = r->strings.text + offset;
            }
            return fail(r, SSX_MD_TYPE_WITHOUT_ELEMENT, r->type_line, name, (slice){0},
                        (slice){0});
        }
    }
    return true;
}

/* A SimpleType with the attributes of its (first) type element, whatever its tag. */
static bool finish_type(reader *r)
{
    r->type_has_element = true;
    if (array_reserve((void **)&r->types, &r->type_capacity, r->type_count + 1,
                      sizeof *r->types, 16)) {
        return out_of_memory(r);
    }
    slice tag = r->xml.open[r->xml.depth - 1].name;
    if (r->fmi1 && tag.length > 4 && memcmp(tag.at + tag.length - 4, "Type", 4) == 0) {
        tag.length -= 4; /* FMI 1.0's RealType is FMI 2.0's Real */
    }
    slice unit = {0}, quantity = {0};
    for (size_t i = 0; i < r->xml.attribute_count; ++i) {
        slice name = r->xml.attributes[i].name;
        if (slice_is(name, "unit")) {
            unit = r->xml.attributes[i].value;
        } else if (slice_is(name, "quantity")) {
            quantity = r->xml.attributes[i].value;
        }
    }
    uint32_t offsets[5];
    slice parts[5] = {r->type_name, tag, r->type_description, unit, quantity};
    for (int k = 0; k < 5; ++k) {
        if (!store(r, parts[k], &offsets[k])) {
            return false;
        }
    }
    r->types[r->type_count] =
        (ssx_md_simple_type){offsets[0], offsets[1], offsets[2], offsets[3], offsets[4]};
    /* a later SimpleType of the same name takes its place */
    if (offsets[0] != 0 &&
        name_index_put(&r->type_index, r->strings.text, offsets[0], (uint32_t)r->type_count,
                       true) == -2) {
        return out_of_memory(r);
    }
    ++r->type_count;
    return true;
}

/* The text of an attribute value: the slice itself when there is nothing to decode, else its
 * decoded copy at the pool's free end, valid until the next store. */
static bool view(reader *r, slice value, slice *text)
{
    if (value.plain) {
        *text = value;
        return true;
    }
    uint32_t offset;
    if (!store(r, value, &offset)) {
        return false;
    }
    *text = (slice){r->strings.text + offset, r->strings.size - offset - 1, true};
    r->strings.size = offset;
    return true;
}

/* The word among first..last the attribute names (fallback when absent), SSX_MD_NONE if none. */
static bool word_attribute(reader *r, slice value, int fallback, int first, int last, int *word)
{
    slice text;
    if (value.at == NULL) {
        *word = fallback;
        return true;
    }
    if (!view(r, value, &text)) {
        return false;
    }
    *word = SSX_MD_NONE;
    for (int candidate = first; candidate <= last; ++candidate) {
        if (is_word(text, candidate)) {
            *word = candidate;
        }
    }
    return true;
}

/* FMI 1.0's causality (input, output, internal, none) and variability (constant, parameter,
 * discrete, continuous) in FMI 2.0's words: a parameter is a fixed parameter (FMI 1.0 sets it
 * before initialization only), internal and none are local. A negated alias is local too: its
 * value reference reads the value it negates, so it can be no port. An unknown word is
 * SSX_MD_NONE (the caller refuses the combination). */
static bool fmi1_words(reader *r, const variable_parts *v, int *causality, int *variability)
{
    /* a view lasts until the next one: each is judged at once */
    slice text = {"internal", 8, true};
    if (v->causality.at != NULL && !view(r, v->causality, &text)) {
        return false;
    }
    bool input = slice_is(text, "input"), output = slice_is(text, "output");
    bool known = input || output || slice_is(text, "internal") || slice_is(text, "none");
    text = (slice){"continuous", 10, true};
    if (v->variability.at != NULL && !view(r, v->variability, &text)) {
        return false;
    }
    bool parameter = slice_is(text, "parameter");
    *variability = parameter                      ? SSX_MD_FIXED
                   : slice_is(text, "constant")   ? SSX_MD_CONSTANT
                   : slice_is(text, "discrete")   ? SSX_MD_DISCRETE
                   : slice_is(text, "continuous") ? SSX_MD_CONTINUOUS
                                                  : SSX_MD_NONE;
    text = (slice){0};
    if (v->alias.at != NULL && !view(r, v->alias, &text)) {
        return false;
    }
    bool negated = slice_is(text, "negatedAlias");
    *causality = !known                ? SSX_MD_NONE
                 : negated             ? SSX_MD_LOCAL
                 : parameter && output ? SSX_MD_LOCAL
                 : parameter           ? SSX_MD_PARAMETER
                 : input               ? SSX_MD_INPUT
                 : output              ? SSX_MD_OUTPUT
                                       : SSX_MD_LOCAL;
    return true;
}

static bool finish_variable(reader *r)
{
    variable_parts *v = &r->variable;
    size_t line = v->line;
    slice none = {0}, text;
    if (v->name.at == NULL) {
        return fail(r, SSX_MD_VARIABLE_WITHOUT_NAME, line, NULL, v->value_reference, none);
    }
    if (r->count == r->capacity && !grow_variables(r)) {
        return out_of_memory(r);
    }
    uint32_t name;
    if (!store(r, v->name, &name)) {
        return false;
    }
    /* A name declared again is read (tools run such FMUs: only the name is ambiguous); the
     * index keeps the first, and the caller learns of the others from duplicate_count. */
    int64_t seen = name_index_put(r->names, r->strings.text, name, (uint32_t)r->count, false);
    if (seen == -2) {
        return out_of_memory(r);
    }
    const char *subject = r->strings.text + name;
    if (seen >= 0) {
        ++r->duplicate_count;
    }
    if (v->type == SSX_MD_NONE) {
        return fail(r, SSX_MD_NO_TYPE_ELEMENT, line, subject, none, none);
    }

    int64_t value_reference;
    if (v->value_reference.at == NULL || !view(r, v->value_reference, &text) ||
        !parse_integer(text.at, text.length, &value_reference)) {
        return fail(r, SSX_MD_VALUE_REFERENCE_NOT_INTEGER, line, r->strings.text + name,
                    v->value_reference, none);
    }
    if (value_reference < 0 || value_reference > (int64_t)UINT32_MAX) {
        return fail(r, SSX_MD_VALUE_REFERENCE_OUT_OF_RANGE, line, r->strings.text + name,
                    v->value_reference, none);
    }

    uint32_t start;
    if (!store(r, v->start, &start)) {
        return false;
    }
    const char *start_text = r->strings.text + start;
    if (start != 0 && !is_start_of(v->type, start_text, strlen(start_text))) {
        r->md->error.word = v->type;
        return fail(r, SSX_MD_BAD_START, line, r->strings.text + name, v->start, none);
    }

    int32_t declared_type = -1;
    if (v->declared_type.at != NULL) {
        uint32_t scratch;
        if (!store(r, v->declared_type, &scratch)) {
            return false;
        }
        int64_t found = name_index_find(&r->type_index, r->strings.text, r->strings.text + scratch);
        if (found < 0) {
            return fail(r, SSX_MD_UNDEFINED_TYPE, line, r->strings.text + name,
                        v->declared_type, none);
        }
        declared_type = (int32_t)found;
        r->strings.size = scratch;
    }

    int causality, variability, initial;
    if (r->fmi1 ? !fmi1_words(r, v, &causality, &variability)
                : (!word_attribute(r, v->causality, SSX_MD_LOCAL, SSX_MD_PARAMETER,
                                   SSX_MD_INDEPENDENT, &causality) ||
                   !word_attribute(r, v->variability, SSX_MD_CONTINUOUS, SSX_MD_CONSTANT,
                                   SSX_MD_CONTINUOUS, &variability))) {
        return false;
    }
    if (!word_attribute(r, r->fmi1 ? none : v->initial, SSX_MD_NONE, SSX_MD_EXACT,
                        SSX_MD_CALCULATED, &initial)) {
        return false;
    }
    subject = r->strings.text + name; /* the pool may have moved */
    bool known = causality != SSX_MD_NONE && variability != SSX_MD_NONE;
    if (known && v->initial.at == NULL) {
        initial = INITIAL_DEFAULT[variability - SSX_MD_CONSTANT][causality - SSX_MD_PARAMETER];
    }
    if (!known || initial == INVALID) {
        slice local = {"local", 5, true}, continuous = {"continuous", 10, true};
        return fail(r, SSX_MD_BAD_COMBINATION, line, subject,
                    v->causality.at != NULL ? v->causality : local,
                    v->variability.at != NULL ? v->variability : continuous);
    }
    if (r->fmi1) {
        initial = SSX_MD_NONE; /* FMI 1.0 has no initial; the table only judged the words */
    } else if (initial == SSX_MD_NONE && v->initial.at != NULL) {
        return fail(r, SSX_MD_BAD_INITIAL, line, subject, v->initial, none);
    }

    uint32_t derivative;
    if (!read_derivative(r, v, &derivative)) {
        return false;
    }
    uint32_t description, unit;
    if (!store(r, v->description, &description) ||
        !store(r, v->type == SSX_MD_REAL ? v->unit : none, &unit)) {
        return false;
    }
    if (r->fmi1 && causality == SSX_MD_OUTPUT && !push_output(r, (uint32_t)r->count)) {
        return false; /* FMI 1.0 has no ModelStructure: an output depends on every input */
    }
    size_t k = r->count++;
    r->name[k] = name;
    r->value_reference[k] = (uint32_t)value_reference;
    r->description[k] = description;
    r->unit[k] = unit;
    r->start[k] = start;
    r->declared_type[k] = declared_type;
    r->derivative[k] = derivative;
    r->type[k] = (uint8_t)v->type;
    r->causality[k] = (uint8_t)causality;
    r->variability[k] = (uint8_t)variability;
    r->initial[k] = (uint8_t)initial;
    return true;
}

/* A Real's derivative attribute: the index (from 1) of the variable it is the time derivative
 * of, 0 when absent. Only a hint (where to look for a slope), so a value that is no index is
 * read as absent; the index is checked against the variables by whoever uses it. */
static bool read_derivative(reader *r, const variable_parts *v, uint32_t *derivative)
{
    *derivative = 0;
    slice text;
    int64_t index;
    if (v->type != SSX_MD_REAL || v->derivative.at == NULL) {
        return true;
    }
    if (!view(r, v->derivative, &text)) {
        return false;
    }
    if (parse_integer(text.at, text.length, &index) && index >= 1 && index <= (int64_t)UINT32_MAX) {
        *derivative = (uint32_t)index;
    }
    return true;
}

/* <Unknown index="3" dependencies="1 2"/> of ModelStructure/Outputs, indices from 1. */
static bool read_unknown(reader *r, size_t line)
{
    slice index = {0}, dependencies = {0}, none = {0};
    for (size_t i = 0; i < r->xml.attribute_count; ++i) {
        if (slice_is(r->xml.attributes[i].name, "index")) {
            index = r->xml.attributes[i].value;
        } else if (slice_is(r->xml.attributes[i].name, "dependencies")) {
            dependencies = r->xml.attributes[i].value;
        }
    }
    uint32_t scratch;
    int64_t value;
    if (!store(r, index, &scratch)) {
        return false;
    }
    const char *scratch_text = r->strings.text + scratch;
    if (scratch == 0 || !parse_integer(scratch_text, strlen(scratch_text), &value) ||
        value < 1 || (uint64_t)value > r->count) {
        return fail(r, SSX_MD_BAD_INDEX, line, NULL, index, none);
    }
    r->strings.size = scratch;
    size_t k = r->output_count;
    if (!push_output(r, (uint32_t)(value - 1))) {
        return false;
    }
    if (dependencies.at != NULL) {
        if (!store(r, dependencies, &scratch)) {
            return false;
        }
        int64_t count = 0;
        const char *p = r->strings.text + scratch;
        for (;;) {
            while (*p == ' ' || (*p >= '\t' && *p <= '\r')) {
                ++p;
            }
            if (*p == '\0') {
                break;
            }
            const char *token = p;
            while (*p != '\0' && *p != ' ' && !(*p >= '\t' && *p <= '\r')) {
                ++p;
            }
            size_t length = (size_t)(p - token);
            if (!parse_integer(token, length, &value) || value < 1 ||
                (uint64_t)value > r->count) {
                return fail(r, SSX_MD_BAD_INDEX, line, NULL, (slice){token, length, true}, none);
            }
            if (array_reserve((void **)&r->dependencies, &r->dependency_capacity,
                              r->dependency_total + 1, sizeof *r->dependencies, 64)) {
                return out_of_memory(r);
            }
            r->dependencies[r->dependency_total++] = (uint32_t)(value - 1);
            ++count;
        }
        r->dependency_count[k] = count;
        r->strings.size = scratch;
    }
    return true;
}

/* An output (its variable's index) depending on everything until its dependencies are read. */
static bool push_output(reader *r, uint32_t index)
{
    size_t k = r->output_count;
    if (array_reserve((void **)&r->output, &r->output_capacity, k + 1, sizeof *r->output, 64)) {
        return out_of_memory(r);
    }
    size_t capacity = r->output_capacity;
    void *first = realloc(r->first_dependency, capacity * sizeof *r->first_dependency);
    if (first != NULL) {
        r->first_dependency = first;
    }
    void *counts = realloc(r->dependency_count, capacity * sizeof *r->dependency_count);
    if (counts != NULL) {
        r->dependency_count = counts;
    }
    if (first == NULL || counts == NULL) {
        return out_of_memory(r);
    }
    r->output[k] = index;
    r->first_dependency[k] = r->dependency_total;
    r->dependency_count[k] = -1;
    r->output_count = k + 1;
    return true;
}

/* The attributes of a root, CoSimulation, ModelExchange or DefaultExperiment element, in place
 * of those of an earlier element of that name. */
static bool keep_attributes(reader *r, slice tag)
{
    size_t kept = 0;
    for (size_t i = 0; i < r->kept_count; ++i) {
        const char *element = r->strings.text + r->kept[i].element;
        if (!(strlen(element) == tag.length && memcmp(element, tag.at, tag.length) == 0)) {
            r->kept[kept++] = r->kept[i];
        }
    }
    r->kept_count = kept;
    uint32_t element;
    if (!store(r, tag, &element)) {
        return false;
    }
    for (size_t i = 0; i < r->xml.attribute_count; ++i) {
        if (array_reserve((void **)&r->kept, &r->kept_capacity, r->kept_count + 1,
                          sizeof *r->kept, 16)) {
            return out_of_memory(r);
        }
        ssx_md_attribute *next = &r->kept[r->kept_count];
        if (!store(r, r->xml.attributes[i].name, &next->name) ||
            !store(r, r->xml.attributes[i].value, &next->value)) {
            return false;
        }
        next->element = element;
        ++r->kept_count;
    }
    return true;
}

/* ------------------------------------------------------------------------------ values */
static bool is_space(char c)
{
    return c == ' ' || (c >= '\t' && c <= '\r');
}

/* Python's int() of the text, for what a modelDescription writes: optional spaces and sign,
 * decimal digits. Values beyond 2**40 in size saturate there (all are out of range). */
static bool parse_integer(const char *text, size_t length, int64_t *value)
{
    const char *p = text, *end = text + length;
    while (p < end && is_space(*p)) {
        ++p;
    }
    while (end > p && is_space(end[-1])) {
        --end;
    }
    bool negative = p < end && *p == '-';
    if (p < end && (*p == '-' || *p == '+')) {
        ++p;
    }
    if (p == end) {
        return false;
    }
    int64_t magnitude = 0;
    for (; p < end; ++p) {
        if (*p < '0' || *p > '9') {
            return false;
        }
        if (magnitude < ((int64_t)1 << 40)) {
            magnitude = 10 * magnitude + (*p - '0');
        }
    }
    *value = negative ? -magnitude : magnitude;
    return true;
}

static bool same_letters(const char *p, const char *end, const char *word)
{
    size_t length = strlen(word);
    if ((size_t)(end - p) != length) {
        return false;
    }
    for (size_t i = 0; i < length; ++i) {
        if ((p[i] | 0x20) != word[i]) {
            return false;
        }
    }
    return true;
}

/* What Python's float() reads (an xs:double): [sign] digits [. digits] [e [sign] digits], at
 * least one digit before the exponent, or [sign] inf, infinity or nan in any case. */
static bool is_real(const char *p, const char *end)
{
    if (p < end && (*p == '+' || *p == '-')) {
        ++p;
    }
    if (same_letters(p, end, "inf") || same_letters(p, end, "infinity") ||
        same_letters(p, end, "nan")) {
        return true;
    }
    size_t digits = 0;
    while (p < end && *p >= '0' && *p <= '9') {
        ++p, ++digits;
    }
    if (p < end && *p == '.') {
        ++p;
        while (p < end && *p >= '0' && *p <= '9') {
            ++p, ++digits;
        }
    }
    if (digits == 0) {
        return false;
    }
    if (p < end && (*p == 'e' || *p == 'E')) {
        ++p;
        if (p < end && (*p == '+' || *p == '-')) {
            ++p;
        }
        size_t exponent_digits = 0;
        while (p < end && *p >= '0' && *p <= '9') {
            ++p, ++exponent_digits;
        }
        if (exponent_digits == 0) {
            return false;
        }
    }
    return p == end;
}

/* Whether text (spaces around it aside) is a value of a variable of that type. */
static bool is_start_of(int type, const char *text, size_t length)
{
    const char *p = text, *end = text + length;
    while (p < end && is_space(*p)) {
        ++p;
    }
    while (end > p && is_space(end[-1])) {
        --end;
    }
    int64_t value;
    switch (type) {
    case SSX_MD_REAL:
        return is_real(p, end);
    case SSX_MD_INTEGER:
    case SSX_MD_ENUMERATION:
        return parse_integer(p, (size_t)(end - p), &value) && value >= INT32_MIN &&
               value <= INT32_MAX;
    case SSX_MD_BOOLEAN: {
        slice word = {p, (size_t)(end - p), true};
        return slice_is(word, "true") || slice_is(word, "false") || slice_is(word, "1") ||
               slice_is(word, "0");
    }
    default:
        return true;
    }
}

/* ------------------------------------------------------------------------------ errors */
static char *copy(slice text)
{
    char *out = malloc(text.length + 1);
    if (out != NULL) {
        size_t length = text.plain ? (memcpy(out, text.at, text.length), text.length)
                                   : xml_decode(out, text);
        out[length] = '\0';
    }
    return out;
}

static bool fail(reader *r, ssx_md_problem problem, size_t line, const char *subject, slice text,
                 slice other)
{
    ssx_md_error *error = &r->md->error;
    if (error->problem != SSX_MD_OK) {
        return false;
    }
    error->problem = problem;
    error->line = line;
    error->count = r->count;
    error->subject = subject != NULL ? copy((slice){subject, strlen(subject), true}) : NULL;
    error->text = text.at != NULL ? copy(text) : NULL;
    error->other = other.at != NULL ? copy(other) : NULL;
    if ((subject != NULL && error->subject == NULL) || (text.at != NULL && error->text == NULL) ||
        (other.at != NULL && error->other == NULL)) {
        error->problem = SSX_MD_NO_MEMORY;
    }
    return false;
}

static bool out_of_memory(reader *r)
{
    if (r->md->error.problem == SSX_MD_OK) {
        r->md->error.problem = SSX_MD_NO_MEMORY;
    }
    return false;
}

/* ------------------------------------------------------------------------------ storage */
static bool store(reader *r, slice text, uint32_t *offset)
{
    return string_pool_add(&r->strings, text, offset) || out_of_memory(r);
}

static bool grow_variables(reader *r)
{
    size_t capacity = r->capacity > 0 ? 2 * r->capacity : 1024;
    void **arrays[] = {(void **)&r->name, (void **)&r->value_reference, (void **)&r->description,
                       (void **)&r->unit, (void **)&r->start, (void **)&r->declared_type,
                       (void **)&r->derivative, (void **)&r->type, (void **)&r->causality,
                       (void **)&r->variability, (void **)&r->initial};
    size_t sizes[] = {4, 4, 4, 4, 4, 4, 4, 1, 1, 1, 1};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; ++k) {
        void *grown = realloc(*arrays[k], capacity * sizes[k]);
        if (grown == NULL) {
            return false;
        }
        *arrays[k] = grown;
    }
    r->capacity = capacity;
    return true;
}

/* Hands what was read (all of it, or what came before a problem) to the ssx_md. */
static void publish(reader *r)
{
    ssx_md *md = r->md;
    char *pool = r->strings.size > 0 ? realloc(r->strings.text, r->strings.size) : NULL;
    /* a failed shrink keeps the larger block */
    md->strings = pool != NULL ? pool : r->strings.text;
    md->attributes = r->kept;
    md->attribute_count = r->kept_count;
    md->types = r->types;
    md->type_count = r->type_count;
    md->variable_count = r->count;
    md->name = r->name;
    md->value_reference = r->value_reference;
    md->description = r->description;
    md->unit = r->unit;
    md->start = r->start;
    md->declared_type = r->declared_type;
    md->derivative = r->derivative;
    md->type = r->type;
    md->causality = r->causality;
    md->variability = r->variability;
    md->initial = r->initial;
    md->output_count = r->output_count;
    md->output = r->output;
    md->first_dependency = r->first_dependency;
    md->dependency_count = r->dependency_count;
    md->dependencies = r->dependencies;
    md->dependency_total = r->dependency_total;
    md->names = r->names;
    md->derivative_count = r->derivative_count;
    md->duplicate_count = r->duplicate_count;
    xml_tokenizer_free(&r->xml);
    name_index_free(&r->type_index);
}

