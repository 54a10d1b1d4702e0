/* modelDescription.xml of FMI 2.0 and FMI 1.0 into compact arrays (the contract is in
 * syssimx_engine.h). FMI 1.0's variables are told in FMI 2.0's words (see finish_variable).
 *
 * Read top-down: the document (prolog, root element, what follows it), the content loop that
 * checks well-formedness and hands every start and end tag to the model layer, the model
 * layer (which elements count where, the checks of a variable), then the storage beneath
 * (string pool, the name index, growable arrays) and the characters (UTF-8, references).
 * Nothing is recursive: an element nested a million deep costs a stack entry, not a frame.
 */
#include "syssimx_engine.h"

#include "array.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    MAX_DEPTH = 10000,     /* deeper nesting is an attack, not a model */
    MAX_ATTRIBUTES = 1000, /* per element: the duplicate check is quadratic */
    SHOWN = 60,            /* characters of a name quoted in a message */
};

typedef struct {
    const char *at; /* NULL: absent */
    size_t length;
    bool plain; /* nothing to decode: no reference, no tab or line break to normalize */
} slice;

typedef struct {
    slice name;
    slice value;
} attribute;

typedef struct {
    slice name;
    size_t line;
} open_element;

/* The ScalarVariable being read: its attributes, then those of its type element. */
typedef struct {
    bool open;
    size_t line;
    slice name, value_reference, causality, variability, initial, description;
    slice alias; /* FMI 1.0 */
    int type; /* SSX_MD_NONE until the type element */
    slice start, unit, declared_type;
} variable_parts;

typedef struct ssx_md_slot {
    uint32_t item; /* the item's index + 1; 0: empty */
    uint32_t key;  /* the item's name in the pool */
    uint32_t hash;
} ssx_md_slot;

struct ssx_md_names {
    ssx_md_slot *slots;
    size_t mask; /* capacity - 1, a power of two */
    size_t count;
};

typedef struct {
    const char *at, *end;
    size_t line;
    ssx_md *md;
    /* the tokenizer */
    open_element *open;
    size_t depth, open_capacity;
    attribute *attributes;
    size_t attribute_count, attribute_capacity;
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
    char *pool;
    size_t pool_size, pool_capacity;
    ssx_md_attribute *kept;
    size_t kept_count, kept_capacity;
    ssx_md_simple_type *types;
    size_t type_count, type_capacity;
    size_t count, capacity; /* variables */
    uint32_t *name, *value_reference, *description, *unit, *start;
    int32_t *declared_type;
    uint8_t *type, *causality, *variability, *initial;
    size_t output_count, output_capacity, dependency_total, dependency_capacity;
    uint32_t *output, *dependencies;
    size_t *first_dependency;
    int64_t *dependency_count;
    size_t derivative_count;
    ssx_md_names *names;
} reader;

/* What each byte may be, looked up once per byte of the text (0x80 and above: a part of a UTF-8
 * sequence, checked on its own). */
enum { NAME_START = 1, NAME_PART = 2, PLAIN_TEXT = 4, PLAIN_VALUE = 8, SPACE = 16 };
static const uint8_t CLASS[256] = {
     0,  0,  0,  0,  0,  0,  0,  0,  0, 16, 16,  0,  0, 16,  0,  0,
     0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,
    28, 12,  4, 12, 12, 12,  0,  4, 12, 12, 12, 12, 12, 14, 14, 12,
    14, 14, 14, 14, 14, 14, 14, 14, 14, 14, 15, 12,  0, 12, 12, 12,
    12, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15,
    15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 12, 12,  8, 12, 15,
    12, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15,
    15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 12, 12, 12, 12, 12,
     3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,
     3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,
     3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,
     3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,
     3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,
     3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,
     3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,
     3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,  3,
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

static bool read_document(reader *r);
static bool read_misc(reader *r, bool before_root);
static bool read_declaration(reader *r);
static bool read_content(reader *r);
static bool read_text(reader *r);
static bool read_start_tag(reader *r);
static bool read_end_tag(reader *r);
static bool read_attributes(reader *r, slice tag, const char *closing, bool *empty);
static bool read_attribute_value(reader *r, slice name, slice *value);
static bool read_comment(reader *r);
static bool read_processing_instruction(reader *r);
static bool read_cdata(reader *r);
static bool read_name(reader *r, slice *name);
static bool skip_space(reader *r);
static bool character(reader *r, const char **cursor);
static bool reference(reader *r, const char **cursor, long *code);
static long utf8(const unsigned char **cursor, const unsigned char *end);
static bool start_element(reader *r, slice tag, size_t line);
static bool end_element(reader *r);
static bool finish_variable(reader *r);
static bool finish_type(reader *r);
static bool read_unknown(reader *r, size_t line);
static bool push_output(reader *r, uint32_t index);
static bool keep_attributes(reader *r, slice tag);
static bool store(reader *r, slice text, uint32_t *offset);
static bool view(reader *r, slice value, slice *text);
static bool grow_variables(reader *r);
static bool parse_integer(const char *text, size_t length, int64_t *value);
static bool is_start_of(int type, const char *text, size_t length);
static size_t decode(char *out, slice text);
static long reference_code(const char **cursor, const char *end);
static bool fail_xml(reader *r, size_t line, const char *format, ...);
static bool fail(reader *r, ssx_md_problem problem, size_t line, const char *subject, slice text,
                 slice other);
static bool out_of_memory(reader *r);
static void publish(reader *r);
static int64_t names_put(ssx_md_names *names, const char *pool, uint32_t key, uint32_t item,
                         bool replace);
static int64_t names_find(const ssx_md_names *names, const char *pool, const char *key);
static void names_free(ssx_md_names *names);

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
    reader r = {.at = xml, .end = xml + size, .line = 1, .md = md};
    r.names = calloc(1, sizeof *r.names);
    r.pool_capacity = 1 + size / 4; /* about what a large model's texts take */
    r.pool = malloc(r.pool_capacity);
    if (r.names == NULL || r.pool == NULL) {
        out_of_memory(&r);
    } else {
        r.pool[0] = '\0'; /* offset 0 means absent */
        r.pool_size = 1;
        read_document(&r);
    }
    publish(&r);
    return md;
}

int64_t ssx_md_find(const ssx_md *md, const char *name)
{
    return names_find(md->names, md->strings, name);
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
        if (size + length <= out_size) {
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
    free((void *)md->type);
    free((void *)md->causality);
    free((void *)md->variability);
    free((void *)md->initial);
    free((void *)md->output);
    free((void *)md->first_dependency);
    free((void *)md->dependency_count);
    free((void *)md->dependencies);
    names_free(md->names);
    free(md->names);
    free(md->error.subject);
    free(md->error.text);
    free(md->error.other);
    free(md);
}

/* ------------------------------------------------------------------------------ the document */
static bool starts_with(const reader *r, const char *prefix)
{
    size_t length = strlen(prefix);
    return (size_t)(r->end - r->at) >= length && memcmp(r->at, prefix, length) == 0;
}

static bool is(slice s, const char *word)
{
    return s.at != NULL && s.length == strlen(word) && memcmp(s.at, word, s.length) == 0;
}

static bool is_word(slice s, int word)
{
    return s.length == WORDS[word].length && memcmp(s.at, WORDS[word].text, s.length) == 0;
}

static int shown(slice s)
{
    return (int)(s.length < SHOWN ? s.length : SHOWN);
}

static bool read_document(reader *r)
{
    if (starts_with(r, "\xEF\xBB\xBF")) { /* a byte order mark */
        r->at += 3;
    }
    if (starts_with(r, "<?xml") && r->end - r->at > 5 && strchr(" \t\r\n", r->at[5]) != NULL) {
        if (!read_declaration(r)) {
            return false;
        }
    }
    if (!read_misc(r, true)) {
        return false;
    }
    if (r->at == r->end) {
        return fail_xml(r, r->line, "no root element");
    }
    if (!read_content(r) || !read_misc(r, false)) {
        return false;
    }
    if (!r->fmi_root) {
        return fail(r, SSX_MD_NO_FMI_ROOT, 1, NULL, (slice){0}, (slice){0});
    }
    return true;
}

/* Whitespace, comments and processing instructions around the root element; before it, stops
 * at its start tag. */
static bool read_misc(reader *r, bool before_root)
{
    for (;;) {
        if (!skip_space(r)) {
            return false;
        }
        if (r->at == r->end) {
            return true;
        }
        if (starts_with(r, "<!--")) {
            if (!read_comment(r)) {
                return false;
            }
        } else if (starts_with(r, "<?")) {
            if (!read_processing_instruction(r)) {
                return false;
            }
        } else if (starts_with(r, "<!DOCTYPE")) {
            return fail_xml(r, r->line, "a DOCTYPE is not accepted in a modelDescription");
        } else if (before_root && *r->at == '<') {
            return true;
        } else {
            return fail_xml(r, r->line, before_root ? "text before the root element"
                                                    : "content after the root element");
        }
    }
}

/* <?xml version="1.0" encoding="UTF-8"?>: FMI 2.0 prescribes UTF-8. */
static bool read_declaration(reader *r)
{
    r->at += 5;
    bool empty;
    if (!read_attributes(r, (slice){"?xml", 4, true}, "?>", &empty)) {
        return false;
    }
    for (size_t i = 0; i < r->attribute_count; ++i) {
        slice value = r->attributes[i].value;
        if (is(r->attributes[i].name, "encoding")) {
            bool utf8_name = value.length == 5 && (strncmp(value.at, "UTF-8", 5) == 0 ||
                                                   strncmp(value.at, "utf-8", 5) == 0);
            if (!utf8_name && !is(value, "US-ASCII") && !is(value, "ASCII")) {
                return fail_xml(r, r->line, "encoding %.*s is not supported (FMI 2.0 requires "
                                "UTF-8)", shown(value), value.at);
            }
        }
    }
    return true;
}

/* The root element and everything in it. */
static bool read_content(reader *r)
{
    do {
        bool done;
        if (r->at == r->end) {
            open_element top = r->open[r->depth - 1];
            return fail_xml(r, r->line, "the document ends inside <%.*s> of line %zu",
                            shown(top.name), top.name.at, top.line);
        }
        char next = r->end - r->at > 1 ? r->at[1] : '\0';
        if (*r->at != '<') {
            done = read_text(r);
        } else if (next == '/') {
            done = read_end_tag(r);
        } else if (next == '?') {
            done = read_processing_instruction(r);
        } else if (next != '!') {
            done = read_start_tag(r);
        } else if (starts_with(r, "<!--")) {
            done = read_comment(r);
        } else if (starts_with(r, "<![CDATA[")) {
            done = read_cdata(r);
        } else {
            done = fail_xml(r, r->line, "markup '<!' is not allowed here");
        }
        if (!done) {
            return false;
        }
    } while (r->depth > 0);
    return true;
}

static bool read_text(reader *r)
{
    const char *p = r->at;
    while (p < r->end && *p != '<') {
        unsigned char c = (unsigned char)*p;
        if (CLASS[c] & PLAIN_TEXT) {
            ++p; /* the common case: plain ASCII */
        } else if (c == '&') {
            long code;
            if (!reference(r, &p, &code)) {
                return false;
            }
        } else if (c == ']' && r->end - p >= 3 && memcmp(p, "]]>", 3) == 0) {
            return fail_xml(r, r->line, "']]>' in text");
        } else if (c == ']') {
            ++p;
        } else if (!character(r, &p)) {
            return false;
        }
    }
    r->at = p;
    return true;
}

static bool read_start_tag(reader *r)
{
    size_t line = r->line;
    ++r->at;
    slice tag;
    if (!read_name(r, &tag)) {
        return fail_xml(r, line, "expected an element name after '<'");
    }
    bool empty;
    if (!read_attributes(r, tag, "/>", &empty)) {
        return false;
    }
    if (r->depth == MAX_DEPTH) {
        return fail_xml(r, line, "elements nested deeper than %d", MAX_DEPTH);
    }
    if (array_reserve((void **)&r->open, &r->open_capacity, r->depth + 1, sizeof *r->open, 16)) {
        return out_of_memory(r);
    }
    r->open[r->depth++] = (open_element){tag, line};
    if (!start_element(r, tag, line)) {
        return false;
    }
    return empty ? end_element(r) : true;
}

static bool read_end_tag(reader *r)
{
    size_t line = r->line;
    r->at += 2;
    slice tag;
    if (!read_name(r, &tag)) {
        return fail_xml(r, line, "expected an element name after '</'");
    }
    if (!skip_space(r)) {
        return false;
    }
    if (r->at == r->end || *r->at != '>') {
        return fail_xml(r, r->line, "expected '>' after '</%.*s'", shown(tag), tag.at);
    }
    ++r->at;
    open_element top = r->open[r->depth - 1];
    if (tag.length != top.name.length || memcmp(tag.at, top.name.at, tag.length) != 0) {
        return fail_xml(r, line, "end tag </%.*s> does not match <%.*s> of line %zu",
                        shown(tag), tag.at, shown(top.name), top.name.at, top.line);
    }
    return end_element(r);
}

/* Attributes up to '>' or `closing` ("/>" of an empty element, "?>" of the declaration),
 * into r->attributes. */
static bool read_attributes(reader *r, slice tag, const char *closing, bool *empty)
{
    r->attribute_count = 0;
    for (;;) {
        const char *before = r->at;
        if (!skip_space(r)) {
            return false;
        }
        bool spaced = r->at > before;
        if (r->at == r->end) {
            return fail_xml(r, r->line, "the document ends inside the tag <%.*s>", shown(tag),
                            tag.at);
        }
        if (*r->at == '>' && closing[0] == '/') {
            ++r->at;
            *empty = false;
            return true;
        }
        if (*r->at == closing[0] && r->end - r->at > 1 && r->at[1] == closing[1]) {
            r->at += 2;
            *empty = true;
            return true;
        }
        attribute next;
        if (!spaced || !read_name(r, &next.name)) {
            return fail_xml(r, r->line, "expected an attribute or the end of the tag <%.*s>",
                            shown(tag), tag.at);
        }
        if (!skip_space(r)) {
            return false;
        }
        if (r->at == r->end || *r->at != '=') {
            return fail_xml(r, r->line, "expected '=' after the attribute %.*s",
                            shown(next.name), next.name.at);
        }
        ++r->at;
        if (!skip_space(r) || !read_attribute_value(r, next.name, &next.value)) {
            return false;
        }
        if (r->attribute_count == MAX_ATTRIBUTES) {
            return fail_xml(r, r->line, "more than %d attributes in <%.*s>", MAX_ATTRIBUTES,
                            shown(tag), tag.at);
        }
        for (size_t i = 0; i < r->attribute_count; ++i) {
            slice seen = r->attributes[i].name;
            if (seen.length == next.name.length &&
                memcmp(seen.at, next.name.at, seen.length) == 0) {
                return fail_xml(r, r->line, "attribute %.*s appears twice in <%.*s>",
                                shown(seen), seen.at, shown(tag), tag.at);
            }
        }
        if (array_reserve((void **)&r->attributes, &r->attribute_capacity,
                          r->attribute_count + 1, sizeof *r->attributes, 16)) {
            return out_of_memory(r);
        }
        r->attributes[r->attribute_count++] = next;
    }
}

static bool read_attribute_value(reader *r, slice name, slice *value)
{
    if (r->at == r->end || (*r->at != '"' && *r->at != '\'')) {
        return fail_xml(r, r->line, "expected a quoted value of the attribute %.*s",
                        shown(name), name.at);
    }
    char quote = *r->at++;
    const char *p = r->at;
    bool plain = true;
    while (p < r->end && *p != quote) {
        unsigned char c = (unsigned char)*p;
        if (CLASS[c] & PLAIN_VALUE || c == '"' || c == '\'') {
            ++p;
        } else if (c == '<') {
            return fail_xml(r, r->line, "'<' in the value of the attribute %.*s",
                            shown(name), name.at);
        } else if (c == '&') {
            long code;
            plain = false;
            if (!reference(r, &p, &code)) {
                return false;
            }
        } else {
            plain = plain && c >= 0x80; /* tabs and line breaks become spaces */
            if (!character(r, &p)) {
                return false;
            }
        }
    }
    if (p == r->end) {
        return fail_xml(r, r->line, "the value of the attribute %.*s is not closed",
                        shown(name), name.at);
    }
    *value = (slice){r->at, (size_t)(p - r->at), plain};
    r->at = p + 1;
    return true;
}

/* Skips checked XML characters from p to the first `close` and past it. `forbidden` (or NULL)
 * may not stand before the close ("--" inside a comment). `what` names the construct begun at
 * `line` for the error. */
static bool skip_to_close(reader *r, const char *p, size_t line, const char *close,
                          const char *forbidden, const char *what)
{
    size_t close_length = strlen(close);
    size_t forbidden_length = forbidden != NULL ? strlen(forbidden) : 0;
    for (;;) {
        if (p == r->end) {
            return fail_xml(r, line, "%s is not closed", what);
        }
        if (*p == close[0] && (size_t)(r->end - p) >= close_length &&
            memcmp(p, close, close_length) == 0) {
            r->at = p + close_length;
            return true;
        }
        if (forbidden != NULL && *p == forbidden[0] &&
            (size_t)(r->end - p) >= forbidden_length &&
            memcmp(p, forbidden, forbidden_length) == 0) {
            return fail_xml(r, r->line, "'%s' inside %s", forbidden, what);
        }
        unsigned char c = (unsigned char)*p;
        if (c >= 0x20 && c < 0x80) {
            ++p;
        } else if (!character(r, &p)) {
            return false;
        }
    }
}

static bool read_comment(reader *r)
{
    return skip_to_close(r, r->at + 4, r->line, "-->", "--", "a comment");
}

static bool read_processing_instruction(reader *r)
{
    size_t line = r->line;
    r->at += 2;
    slice target;
    if (!read_name(r, &target)) {
        return fail_xml(r, line, "expected a target after '<?'");
    }
    if (target.length == 3 && (target.at[0] | 0x20) == 'x' && (target.at[1] | 0x20) == 'm' &&
        (target.at[2] | 0x20) == 'l') {
        return fail_xml(r, line, "an XML declaration is allowed only at the start");
    }
    const char *p = r->at;
    if (p < r->end && !starts_with(r, "?>") && strchr(" \t\r\n", *p) == NULL) {
        return fail_xml(r, line, "expected a space after '<?%.*s'", shown(target), target.at);
    }
    return skip_to_close(r, p, line, "?>", NULL, "a processing instruction");
}

static bool read_cdata(reader *r)
{
    return skip_to_close(r, r->at + 9, r->line, "]]>", NULL, "a CDATA section");
}

static bool name_start(unsigned char c)
{
    return CLASS[c] & NAME_START;
}

static bool name_part(unsigned char c)
{
    return CLASS[c] & NAME_PART;
}

/* A name at the cursor (false, with nothing set, when there is none). */
static bool read_name(reader *r, slice *name)
{
    const unsigned char *p = (const unsigned char *)r->at;
    const unsigned char *end = (const unsigned char *)r->end;
    if (p == end || !name_start(*p)) {
        return false;
    }
    while (p < end && name_part(*p)) {
        if (*p >= 0x80) {
            long code = utf8(&p, end);
            if (code < 0) {
                return false;
            }
        } else {
            ++p;
        }
    }
    *name = (slice){r->at, (size_t)((const char *)p - r->at), true};
    r->at = (const char *)p;
    return true;
}

/* Always true: the signature lets calls chain with the readers that can fail. */
static bool skip_space(reader *r)
{
    while (r->at < r->end && CLASS[(unsigned char)*r->at] & SPACE) {
        r->line += *r->at == '\n';
        ++r->at;
    }
    return true;
}

/* ------------------------------------------------------------------------------ the model */
static bool start_element(reader *r, slice tag, size_t line)
{
    switch (r->depth) {
    case 1:
        if (!is(tag, "fmiModelDescription")) {
            return true;
        }
        r->fmi_root = true;
        if (!keep_attributes(r, tag)) {
            return false;
        }
        for (size_t i = 0; i < r->attribute_count; ++i) {
            if (is(r->attributes[i].name, "fmiVersion")) {
                slice version;
                if (!view(r, r->attributes[i].value, &version)) {
                    return false;
                }
                r->fmi1 = is(version, "1.0");
                return is(version, "2.0") || r->fmi1
                           ? true
                           : fail(r, SSX_MD_NOT_FMI2, line, NULL, version, (slice){0});
            }
        }
        /* before reading variables of another schema */
        return fail(r, SSX_MD_NOT_FMI2, line, NULL, (slice){0}, (slice){0});
    case 2:
        r->section = tag;
        if (is(tag, "CoSimulation") || is(tag, "ModelExchange") || is(tag, "DefaultExperiment")) {
            return keep_attributes(r, tag);
        }
        return true;
    case 3:
        r->subsection = tag;
        if (is(tag, "ScalarVariable") && is(r->section, "ModelVariables")) {
            variable_parts *v = &r->variable;
            *v = (variable_parts){.open = true, .line = line};
            for (size_t i = 0; i < r->attribute_count; ++i) {
                slice name = r->attributes[i].name, value = r->attributes[i].value;
                if (is(name, "name")) {
                    v->name = value;
                } else if (is(name, "valueReference")) {
                    v->value_reference = value;
                } else if (is(name, "causality")) {
                    v->causality = value;
                } else if (is(name, "variability")) {
                    v->variability = value;
                } else if (is(name, "initial")) {
                    v->initial = value;
                } else if (is(name, "description")) {
                    v->description = value;
                } else if (is(name, "alias")) {
                    v->alias = value;
                }
            }
        } else if (is(tag, r->fmi1 ? "Type" : "SimpleType") &&
                   is(r->section, "TypeDefinitions")) {
            r->in_type = true;
            r->type_has_element = false;
            r->type_line = line;
            r->type_name = r->type_description = (slice){0};
            for (size_t i = 0; i < r->attribute_count; ++i) {
                if (is(r->attributes[i].name, "name")) {
                    r->type_name = r->attributes[i].value;
                } else if (is(r->attributes[i].name, "description")) {
                    r->type_description = r->attributes[i].value;
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
            for (size_t i = 0; v->type != SSX_MD_NONE && i < r->attribute_count; ++i) {
                slice name = r->attributes[i].name, value = r->attributes[i].value;
                if (is(name, "start")) {
                    v->start = value;
                } else if (is(name, "unit")) {
                    v->unit = value;
                } else if (is(name, "declaredType")) {
                    v->declared_type = value;
                }
            }
            return true;
        }
        if (r->in_type) {
            return r->type_has_element ? true : finish_type(r);
        }
        if (r->fmi1 && is(tag, "Capabilities") && is(r->section, "Implementation")) {
            return keep_attributes(r, tag); /* of CoSimulation_StandAlone or _Tool */
        }
        if (is(tag, "Unknown") && is(r->subsection, "Outputs") &&
            is(r->section, "ModelStructure")) {
            return read_unknown(r, line); /* syssimx reads the feedthrough of outputs only */
        }
        if (is(tag, "Unknown") && is(r->subsection, "Derivatives") &&
            is(r->section, "ModelStructure")) {
            ++r->derivative_count; /* a Model Exchange FMU's number of continuous states */
        }
        return true;
    default:
        return true;
    }
}

static bool end_element(reader *r)
{
    --r->depth;
    if (r->depth != 2) {
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
                name = r->pool + offset;
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
    slice tag = r->open[r->depth - 1].name;
    if (r->fmi1 && tag.length > 4 && memcmp(tag.at + tag.length - 4, "Type", 4) == 0) {
        tag.length -= 4; /* FMI 1.0's RealType is FMI 2.0's Real */
    }
    slice unit = {0}, quantity = {0};
    for (size_t i = 0; i < r->attribute_count; ++i) {
        slice name = r->attributes[i].name;
        if (is(name, "unit")) {
            unit = r->attributes[i].value;
        } else if (is(name, "quantity")) {
            quantity = r->attributes[i].value;
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
        names_put(&r->type_index, r->pool, offsets[0], (uint32_t)r->type_count, true) == -2) {
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
    *text = (slice){r->pool + offset, r->pool_size - offset - 1, true};
    r->pool_size = offset;
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
    bool input = is(text, "input"), output = is(text, "output");
    bool known = input || output || is(text, "internal") || is(text, "none");
    text = (slice){"continuous", 10, true};
    if (v->variability.at != NULL && !view(r, v->variability, &text)) {
        return false;
    }
    bool parameter = is(text, "parameter");
    *variability = parameter                      ? SSX_MD_FIXED
                   : is(text, "constant")         ? SSX_MD_CONSTANT
                   : is(text, "discrete")         ? SSX_MD_DISCRETE
                   : is(text, "continuous")       ? SSX_MD_CONTINUOUS
                                                  : SSX_MD_NONE;
    text = (slice){0};
    if (v->alias.at != NULL && !view(r, v->alias, &text)) {
        return false;
    }
    bool negated = is(text, "negatedAlias");
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
    int64_t seen = names_put(r->names, r->pool, name, (uint32_t)r->count, false);
    if (seen == -2) {
        return out_of_memory(r);
    }
    const char *subject = r->pool + name;
    if (seen >= 0) {
        return fail(r, SSX_MD_DUPLICATE_NAME, line, subject, none, none);
    }
    if (v->type == SSX_MD_NONE) {
        return fail(r, SSX_MD_NO_TYPE_ELEMENT, line, subject, none, none);
    }

    int64_t value_reference;
    if (v->value_reference.at == NULL || !view(r, v->value_reference, &text) ||
        !parse_integer(text.at, text.length, &value_reference)) {
        return fail(r, SSX_MD_VALUE_REFERENCE_NOT_INTEGER, line, r->pool + name,
                    v->value_reference, none);
    }
    if (value_reference < 0 || value_reference > (int64_t)UINT32_MAX) {
        return fail(r, SSX_MD_VALUE_REFERENCE_OUT_OF_RANGE, line, r->pool + name,
                    v->value_reference, none);
    }

    uint32_t start;
    if (!store(r, v->start, &start)) {
        return false;
    }
    if (start != 0 && !is_start_of(v->type, r->pool + start, strlen(r->pool + start))) {
        r->md->error.word = v->type;
        return fail(r, SSX_MD_BAD_START, line, r->pool + name, v->start, none);
    }

    int32_t declared_type = -1;
    if (v->declared_type.at != NULL) {
        uint32_t scratch;
        if (!store(r, v->declared_type, &scratch)) {
            return false;
        }
        int64_t found = names_find(&r->type_index, r->pool, r->pool + scratch);
        if (found < 0) {
            return fail(r, SSX_MD_UNDEFINED_TYPE, line, r->pool + name, v->declared_type, none);
        }
        declared_type = (int32_t)found;
        r->pool_size = scratch;
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
    subject = r->pool + name; /* the pool may have moved */
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
    if (initial == SSX_MD_NONE && v->initial.at != NULL) {
        return fail(r, SSX_MD_BAD_INITIAL, line, subject, v->initial, none);
    }
    if (r->fmi1) {
        initial = SSX_MD_NONE; /* FMI 1.0 has no initial; the table only judged the words */
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
    r->type[k] = (uint8_t)v->type;
    r->causality[k] = (uint8_t)causality;
    r->variability[k] = (uint8_t)variability;
    r->initial[k] = (uint8_t)initial;
    return true;
}

/* <Unknown index="3" dependencies="1 2"/> of ModelStructure/Outputs, indices from 1. */
static bool read_unknown(reader *r, size_t line)
{
    slice index = {0}, dependencies = {0}, none = {0};
    for (size_t i = 0; i < r->attribute_count; ++i) {
        if (is(r->attributes[i].name, "index")) {
            index = r->attributes[i].value;
        } else if (is(r->attributes[i].name, "dependencies")) {
            dependencies = r->attributes[i].value;
        }
    }
    uint32_t scratch;
    int64_t value;
    if (!store(r, index, &scratch)) {
        return false;
    }
    if (scratch == 0 || !parse_integer(r->pool + scratch, strlen(r->pool + scratch), &value) ||
        value < 1 || (uint64_t)value > r->count) {
        return fail(r, SSX_MD_BAD_INDEX, line, NULL, index, none);
    }
    r->pool_size = scratch;
    size_t k = r->output_count;
    if (!push_output(r, (uint32_t)(value - 1))) {
        return false;
    }
    if (dependencies.at != NULL) {
        if (!store(r, dependencies, &scratch)) {
            return false;
        }
        int64_t count = 0;
        const char *p = r->pool + scratch;
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
        r->pool_size = scratch;
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
        const char *element = r->pool + r->kept[i].element;
        if (!(strlen(element) == tag.length && memcmp(element, tag.at, tag.length) == 0)) {
            r->kept[kept++] = r->kept[i];
        }
    }
    r->kept_count = kept;
    uint32_t element;
    if (!store(r, tag, &element)) {
        return false;
    }
    for (size_t i = 0; i < r->attribute_count; ++i) {
        if (array_reserve((void **)&r->kept, &r->kept_capacity, r->kept_count + 1,
                          sizeof *r->kept, 16)) {
            return out_of_memory(r);
        }
        ssx_md_attribute *next = &r->kept[r->kept_count];
        if (!store(r, r->attributes[i].name, &next->name) ||
            !store(r, r->attributes[i].value, &next->value)) {
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
        return is(word, "true") || is(word, "false") || is(word, "1") || is(word, "0");
    }
    default:
        return true;
    }
}

/* ------------------------------------------------------------------------------ errors */
static bool fail_xml(reader *r, size_t line, const char *format, ...)
{
    ssx_md_error *error = &r->md->error;
    if (error->problem == SSX_MD_OK) {
        error->problem = SSX_MD_NOT_XML;
        error->line = line;
        va_list arguments;
        va_start(arguments, format);
        vsnprintf(error->detail, sizeof error->detail, format, arguments);
        va_end(arguments);
    }
    return false;
}

static char *copy(slice text)
{
    char *out = malloc(text.length + 1);
    if (out != NULL) {
        size_t length = text.plain ? (memcpy(out, text.at, text.length), text.length)
                                   : decode(out, text);
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
/* The text, decoded, appended to the pool: *offset is where it starts (0 when absent). */
static bool store(reader *r, slice text, uint32_t *offset)
{
    if (text.at == NULL) {
        *offset = 0;
        return true;
    }
    /* decoding never lengthens a text */
    if (array_reserve((void **)&r->pool, &r->pool_capacity, r->pool_size + text.length + 1, 1,
                      4096)) {
        return out_of_memory(r);
    }
    char *out = r->pool + r->pool_size;
    size_t length = text.plain ? (memcpy(out, text.at, text.length), text.length)
                               : decode(out, text);
    out[length] = '\0';
    *offset = (uint32_t)r->pool_size;
    r->pool_size += length + 1;
    return true;
}

/* An attribute value as XML delivers it: references resolved, each tab, line break or CR LF
 * pair one space. Returns the length written. */
static size_t decode(char *out, slice text)
{
    const char *p = text.at, *end = text.at + text.length;
    size_t n = 0;
    while (p < end) {
        char c = *p;
        if (c == '&') {
            long code = reference_code(&p, end); /* valid: checked while scanning */
            if (code < 0) {
                code = '&'; /* never: but an unchecked text must not stop the loop */
                ++p;
            }
            if (code < 0x80) {
                out[n++] = (char)code;
            } else if (code < 0x800) {
                out[n++] = (char)(0xC0 | (code >> 6));
                out[n++] = (char)(0x80 | (code & 0x3F));
            } else if (code < 0x10000) {
                out[n++] = (char)(0xE0 | (code >> 12));
                out[n++] = (char)(0x80 | ((code >> 6) & 0x3F));
                out[n++] = (char)(0x80 | (code & 0x3F));
            } else {
                out[n++] = (char)(0xF0 | (code >> 18));
                out[n++] = (char)(0x80 | ((code >> 12) & 0x3F));
                out[n++] = (char)(0x80 | ((code >> 6) & 0x3F));
                out[n++] = (char)(0x80 | (code & 0x3F));
            }
            continue;
        }
        if (c == '\r' && p + 1 < end && p[1] == '\n') {
            ++p; /* the pair is one line break */
            continue;
        }
        out[n++] = (c == '\t' || c == '\n' || c == '\r') ? ' ' : c;
        ++p;
    }
    return n;
}

static bool grow_variables(reader *r)
{
    size_t capacity = r->capacity > 0 ? 2 * r->capacity : 1024;
    void **arrays[] = {(void **)&r->name, (void **)&r->value_reference, (void **)&r->description,
                       (void **)&r->unit, (void **)&r->start, (void **)&r->declared_type,
                       (void **)&r->type, (void **)&r->causality, (void **)&r->variability,
                       (void **)&r->initial};
    size_t sizes[] = {4, 4, 4, 4, 4, 4, 1, 1, 1, 1};
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
    char *pool = r->pool_size > 0 ? realloc(r->pool, r->pool_size) : NULL;
    md->strings = pool != NULL ? pool : r->pool; /* a failed shrink keeps the larger block */
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
    free(r->open);
    free(r->attributes);
    names_free(&r->type_index);
}

/* FNV-1a: names of generated models differ in few characters, and it mixes each of them. */
static uint32_t hash_of(const char *key)
{
    uint32_t hash = 2166136261u;
    for (const unsigned char *p = (const unsigned char *)key; *p != '\0'; ++p) {
        hash = (hash ^ *p) * 16777619u;
    }
    return hash;
}

static int64_t names_find(const ssx_md_names *names, const char *pool, const char *key)
{
    if (names == NULL || names->slots == NULL) {
        return -1;
    }
    uint32_t hash = hash_of(key);
    for (size_t i = hash & names->mask;; i = (i + 1) & names->mask) {
        const ssx_md_slot *slot = &names->slots[i];
        if (slot->item == 0) {
            return -1;
        }
        if (slot->hash == hash && strcmp(pool + slot->key, key) == 0) {
            return (int64_t)slot->item - 1;
        }
    }
}

static bool names_grow(ssx_md_names *names)
{
    size_t capacity = names->slots != NULL ? 2 * (names->mask + 1) : 1024;
    ssx_md_slot *slots = calloc(capacity, sizeof *slots);
    if (slots == NULL) {
        return false;
    }
    for (size_t i = 0; names->slots != NULL && i <= names->mask; ++i) {
        ssx_md_slot slot = names->slots[i];
        if (slot.item != 0) {
            size_t j = slot.hash & (capacity - 1);
            while (slots[j].item != 0) {
                j = (j + 1) & (capacity - 1);
            }
            slots[j] = slot;
        }
    }
    free(names->slots);
    names->slots = slots;
    names->mask = capacity - 1;
    return true;
}

/* Enters item under the name at pool + key. If the name is there already, returns the item it
 * names (and puts item in its place when replace); -1 after entering it; -2: out of memory. */
static int64_t names_put(ssx_md_names *names, const char *pool, uint32_t key, uint32_t item,
                         bool replace)
{
    if ((names->slots == NULL || 2 * (names->count + 1) > names->mask + 1) &&
        !names_grow(names)) {
        return -2;
    }
    uint32_t hash = hash_of(pool + key);
    for (size_t i = hash & names->mask;; i = (i + 1) & names->mask) {
        ssx_md_slot *slot = &names->slots[i];
        if (slot->item == 0) {
            *slot = (ssx_md_slot){item + 1, key, hash};
            ++names->count;
            return -1;
        }
        if (slot->hash == hash && strcmp(pool + slot->key, pool + key) == 0) {
            int64_t previous = (int64_t)slot->item - 1;
            if (replace) {
                *slot = (ssx_md_slot){item + 1, key, hash};
            }
            return previous;
        }
    }
}

static void names_free(ssx_md_names *names)
{
    if (names != NULL) {
        free(names->slots);
    }
}

/* ------------------------------------------------------------------------------ characters */
static bool xml_char(long code)
{
    return code == 0x9 || code == 0xA || code == 0xD || (code >= 0x20 && code <= 0xD7FF) ||
           (code >= 0xE000 && code <= 0xFFFD) || (code >= 0x10000 && code <= 0x10FFFF);
}

/* A character at the cursor that is not printable ASCII: a tab, line break or carriage return,
 * or the UTF-8 sequence of a character XML allows. */
static bool character(reader *r, const char **cursor)
{
    unsigned char c = (unsigned char)**cursor;
    if (c == '\n' || c == '\t' || c == '\r') {
        r->line += c == '\n';
        ++*cursor;
        return true;
    }
    if (c < 0x80) {
        return fail_xml(r, r->line, "character U+%04X is not allowed in XML", c);
    }
    const unsigned char *p = (const unsigned char *)*cursor;
    long code = utf8(&p, (const unsigned char *)r->end);
    if (code < 0) {
        return fail_xml(r, r->line, "invalid UTF-8 (a sequence starting with byte 0x%02X)", c);
    }
    if (!xml_char(code)) {
        return fail_xml(r, r->line, "character U+%04lX is not allowed in XML", code);
    }
    *cursor = (const char *)p;
    return true;
}

/* The code point of the UTF-8 sequence at the cursor (advanced past it), or -1 when the bytes
 * are not the shortest encoding of a scalar value. */
static long utf8(const unsigned char **cursor, const unsigned char *end)
{
    const unsigned char *p = *cursor;
    unsigned char c = *p;
    int length;
    long code;
    unsigned char low = 0x80, high = 0xBF; /* the bounds of the second byte */
    if (c >= 0xC2 && c <= 0xDF) {
        length = 2, code = c & 0x1F;
    } else if (c >= 0xE0 && c <= 0xEF) {
        length = 3, code = c & 0x0F;
        low = c == 0xE0 ? 0xA0 : 0x80;  /* no overlong form */
        high = c == 0xED ? 0x9F : 0xBF; /* no surrogate */
    } else if (c >= 0xF0 && c <= 0xF4) {
        length = 4, code = c & 0x07;
        low = c == 0xF0 ? 0x90 : 0x80;
        high = c == 0xF4 ? 0x8F : 0xBF; /* nothing beyond U+10FFFF */
    } else {
        return -1;
    }
    if (end - p < length || p[1] < low || p[1] > high) {
        return -1;
    }
    for (int i = 1; i < length; ++i) {
        if ((p[i] & 0xC0) != 0x80) {
            return -1;
        }
        code = (code << 6) | (p[i] & 0x3F);
    }
    *cursor = p + length;
    return code;
}

/* The code point of the reference at the cursor ("&lt;", "&#10;", "&#x20AC;"), the cursor then
 * past its ';'; -1 when it is none of the predefined entities or a valid character. */
static long reference_code(const char **cursor, const char *end)
{
    static const struct {
        const char *name;
        long code;
    } ENTITIES[] = {{"lt;", '<'}, {"gt;", '>'}, {"amp;", '&'}, {"apos;", '\''}, {"quot;", '"'}};
    const char *p = *cursor + 1;
    if (p < end && *p == '#') {
        ++p;
        int base = 10;
        if (p < end && *p == 'x') {
            base = 16;
            ++p;
        }
        long code = 0;
        const char *digits = p;
        for (; p < end && *p != ';'; ++p) {
            char c = *p;
            int digit = c >= '0' && c <= '9'                 ? c - '0'
                        : base == 16 && c >= 'a' && c <= 'f' ? c - 'a' + 10
                        : base == 16 && c >= 'A' && c <= 'F' ? c - 'A' + 10
                                                             : -1;
            if (digit < 0) {
                return -1;
            }
            code = code > 0x10FFFF ? code : code * base + digit; /* stops growing once invalid */
        }
        if (p == end || p == digits || !xml_char(code)) {
            return -1;
        }
        *cursor = p + 1;
        return code;
    }
    for (size_t i = 0; i < sizeof ENTITIES / sizeof ENTITIES[0]; ++i) {
        size_t length = strlen(ENTITIES[i].name);
        if ((size_t)(end - p) >= length && memcmp(p, ENTITIES[i].name, length) == 0) {
            *cursor = p + length;
            return ENTITIES[i].code;
        }
    }
    return -1;
}

static bool reference(reader *r, const char **cursor, long *code)
{
    const char *at = *cursor;
    *code = reference_code(cursor, r->end);
    if (*code < 0) {
        size_t length = 1;
        while (at + length < r->end && length < 12 && at[length] != ';' && at[length] != '<') {
            ++length;
        }
        return fail_xml(r, r->line, "'%.*s...' is neither a predefined entity (&lt; &gt; &amp; "
                        "&apos; &quot;) nor a character reference", (int)length, at);
    }
    return true;
}
