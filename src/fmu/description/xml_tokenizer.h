/* The XML 1.0 tokenizer of the modelDescription reader: checks a document's well-formedness
 * and hands each start and end tag, with its attributes, to a handler (the FMI model layer).
 * It knows nothing of FMI. */
#ifndef SSX_XML_TOKENIZER_H
#define SSX_XML_TOKENIZER_H

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "syssimx_engine.h"

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

/* What the tokenizer reports; each returns false to stop, with the error set. */
typedef struct {
    /* The element just opened: its attributes are the tokenizer's `attributes`. */
    bool (*start_element)(void *user, slice tag, size_t line);
    /* The innermost open element closed; `depth` counts the elements still open. */
    bool (*end_element)(void *user);
} xml_handler;

typedef struct {
    const char *at, *end;
    size_t line;
    ssx_md_error *error; /* the first problem, kept */
    xml_handler handler;
    void *user;
    open_element *open; /* the open elements, outermost first */
    size_t depth, open_capacity;
    attribute *attributes; /* those of the tag read last */
    size_t attribute_count, attribute_capacity;
} xml_tokenizer;

/* Reads the whole document: prolog, root element, what follows it. */
bool xml_read_document(xml_tokenizer *r);
void xml_tokenizer_free(xml_tokenizer *r);

/* An attribute value as XML delivers it: references resolved, each tab, line break or CR LF
 * pair one space. Returns the length written (never more than the text's). */
size_t xml_decode(char *out, slice text);

static inline bool slice_is(slice s, const char *word)
{
    return s.at != NULL && s.length == strlen(word) && memcmp(s.at, word, s.length) == 0;
}

#endif
