/* The XML tokenizer (see xml_tokenizer.h).
 *
 * Read top-down: the document (prolog, root element, what follows it), the content loop that
 * checks well-formedness and hands every start and end tag to the handler, then the
 * characters (UTF-8, references). Nothing is recursive: an element nested a million deep costs
 * a stack entry, not a frame.
 */
#include "xml_tokenizer.h"

#include "array.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

enum {
    MAX_DEPTH = 10000,     /* deeper nesting is an attack, not a model */
    MAX_ATTRIBUTES = 1000, /* per element: the duplicate check is quadratic */
    SHOWN = 60,            /* characters of a name quoted in a message */
};

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

static bool read_misc(xml_tokenizer *r, bool before_root);
static bool read_declaration(xml_tokenizer *r);
static bool read_content(xml_tokenizer *r);
static bool read_text(xml_tokenizer *r);
static bool read_start_tag(xml_tokenizer *r);
static bool read_end_tag(xml_tokenizer *r);
static bool read_attributes(xml_tokenizer *r, slice tag, const char *closing, bool *empty);
static bool read_attribute_value(xml_tokenizer *r, slice name, slice *value);
static bool read_comment(xml_tokenizer *r);
static bool read_processing_instruction(xml_tokenizer *r);
static bool read_cdata(xml_tokenizer *r);
static bool read_name(xml_tokenizer *r, slice *name);
static bool skip_space(xml_tokenizer *r);
static bool character(xml_tokenizer *r, const char **cursor);
static bool reference(xml_tokenizer *r, const char **cursor, long *code);
static long utf8(const unsigned char **cursor, const unsigned char *end);
static bool end_element(xml_tokenizer *r);
static bool fail_xml(xml_tokenizer *r, size_t line, const char *format, ...);
static bool out_of_memory(xml_tokenizer *r);

/* ------------------------------------------------------------------------------ the document */
static bool starts_with(const xml_tokenizer *r, const char *prefix)
{
    size_t length = strlen(prefix);
    return (size_t)(r->end - r->at) >= length && memcmp(r->at, prefix, length) == 0;
}

static int shown(slice s)
{
    return (int)(s.length < SHOWN ? s.length : SHOWN);
}

bool xml_read_document(xml_tokenizer *r)
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
    return true;
}

/* Whitespace, comments and processing instructions around the root element; before it, stops
 * at its start tag. */
static bool read_misc(xml_tokenizer *r, bool before_root)
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
static bool read_declaration(xml_tokenizer *r)
{
    r->at += 5;
    bool empty;
    if (!read_attributes(r, (slice){"?xml", 4, true}, "?>", &empty)) {
        return false;
    }
    for (size_t i = 0; i < r->attribute_count; ++i) {
        slice value = r->attributes[i].value;
        if (slice_is(r->attributes[i].name, "encoding")) {
            bool utf8_name = value.length == 5 && (strncmp(value.at, "UTF-8", 5) == 0 ||
                                                   strncmp(value.at, "utf-8", 5) == 0);
            if (!utf8_name && !slice_is(value, "US-ASCII") && !slice_is(value, "ASCII")) {
                return fail_xml(r, r->line, "encoding %.*s is not supported (FMI 2.0 requires "
                                "UTF-8)", shown(value), value.at);
            }
        }
    }
    return true;
}

/* The root element and everything in it. */
static bool read_content(xml_tokenizer *r)
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

static bool read_text(xml_tokenizer *r)
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

static bool read_start_tag(xml_tokenizer *r)
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
    if (!r->handler.start_element(r->user, tag, line)) {
        return false;
    }
    return empty ? end_element(r) : true;
}

static bool read_end_tag(xml_tokenizer *r)
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
    if (r->depth == 0) { /* the root's place: nothing is open to close */
        return fail_xml(r, line, "end tag </%.*s> without a start tag", shown(tag), tag.at);
    }
    open_element top = r->open[r->depth - 1];
    if (tag.length != top.name.length || memcmp(tag.at, top.name.at, tag.length) != 0) {
        return fail_xml(r, line, "end tag </%.*s> does not match <%.*s> of line %zu",
                        shown(tag), tag.at, shown(top.name), top.name.at, top.line);
    }
    return end_element(r);
}

/* Attributes up to '>' or `closing` ("/>" of an empty element, "?>" of the declaration),
 * into r->attributes. */
static bool read_attributes(xml_tokenizer *r, slice tag, const char *closing, bool *empty)
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

static bool read_attribute_value(xml_tokenizer *r, slice name, slice *value)
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
static bool skip_to_close(xml_tokenizer *r, const char *p, size_t line, const char *close,
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

static bool read_comment(xml_tokenizer *r)
{
    return skip_to_close(r, r->at + 4, r->line, "-->", "--", "a comment");
}

static bool read_processing_instruction(xml_tokenizer *r)
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

static bool read_cdata(xml_tokenizer *r)
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
static bool read_name(xml_tokenizer *r, slice *name)
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
static bool skip_space(xml_tokenizer *r)
{
    while (r->at < r->end && CLASS[(unsigned char)*r->at] & SPACE) {
        r->line += *r->at == '\n';
        ++r->at;
    }
    return true;
}


static bool end_element(xml_tokenizer *r)
{
    --r->depth;
    return r->handler.end_element(r->user);
}

void xml_tokenizer_free(xml_tokenizer *r)
{
    free(r->open);
    free(r->attributes);
}

/* ------------------------------------------------------------------------------ errors */
static bool fail_xml(xml_tokenizer *r, size_t line, const char *format, ...)
{
    ssx_md_error *error = r->error;
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

static bool out_of_memory(xml_tokenizer *r)
{
    if (r->error->problem == SSX_MD_OK) {
        r->error->problem = SSX_MD_NO_MEMORY;
    }
    return false;
}

/* ------------------------------------------------------------------------------ characters */
static bool xml_char(long code)
{
    return code == 0x9 || code == 0xA || code == 0xD || (code >= 0x20 && code <= 0xD7FF) ||
           (code >= 0xE000 && code <= 0xFFFD) || (code >= 0x10000 && code <= 0x10FFFF);
}

/* A character at the cursor that is not printable ASCII: a tab, line break or carriage return,
 * or the UTF-8 sequence of a character XML allows. */
static bool character(xml_tokenizer *r, const char **cursor)
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

static bool reference(xml_tokenizer *r, const char **cursor, long *code)
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

size_t xml_decode(char *out, slice text)
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

