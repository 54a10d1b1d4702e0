/* Writing a plan: the header, then each record as its keyword and values. A double is written
 * in the fewest digits (15, 16 or 17) that read back to the same double, so that reading what
 * was written and writing it again gives the same text; a string stays UTF-8 text. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plan.h"

typedef struct {
    char *text;
    size_t size;
    size_t capacity;
    int failed;
} text_buffer;

static void append(text_buffer *b, const char *bytes, size_t n)
{
    if (b->failed) {
        return;
    }
    if (b->size + n + 1 > b->capacity) {
        size_t wanted = b->capacity < 256 ? 256 : b->capacity;
        while (wanted < b->size + n + 1) {
            if (wanted > SIZE_MAX / 2) {
                b->failed = 1;
                return;
            }
            wanted *= 2;
        }
        char *grown = realloc(b->text, wanted);
        if (grown == NULL) {
            b->failed = 1;
            return;
        }
        b->text = grown;
        b->capacity = wanted;
    }
    memcpy(b->text + b->size, bytes, n);
    b->size += n;
    b->text[b->size] = '\0';
}

static void append_text(text_buffer *b, const char *text)
{
    append(b, text, strlen(text));
}

static void append_double(text_buffer *b, double value)
{
    char text[40];
    if (isnan(value)) {
        append_text(b, "nan");
        return;
    }
    if (isinf(value)) {
        append_text(b, value > 0 ? "inf" : "-inf");
        return;
    }
    for (int digits = 15; digits <= 17; ++digits) {
        snprintf(text, sizeof text, "%.*g", digits, value);
        if (strtod(text, NULL) == value) {
            break;
        }
    }
    append_text(b, text);
}

/* The length of the well-formed UTF-8 sequence at s (n bytes left), 0 when there is none. */
static size_t utf8_sequence(const unsigned char *s, size_t n)
{
    size_t length = s[0] >= 0xf0 && s[0] <= 0xf4 ? 4 : s[0] >= 0xe0 ? 3 : s[0] >= 0xc2 ? 2 : 0;
    if (length == 0 || length > n) {
        return 0;
    }
    for (size_t k = 1; k < length; ++k) {
        if ((s[k] & 0xc0) != 0x80) {
            return 0;
        }
    }
    return length;
}

/* A string in quotes: the escapes for the quote, the backslash, newline and tab, \xHH for the
 * other control bytes and for bytes that are no UTF-8 (Binary values), the rest as it is. */
static void append_string(text_buffer *b, const char *bytes, size_t n)
{
    append(b, "\"", 1);
    size_t run = 0; /* bytes that stand for themselves, written together */
    for (size_t k = 0; k < n; ++k) {
        unsigned char c = (unsigned char)bytes[k];
        const char *escape = c == '"' ? "\\\"" : c == '\\' ? "\\\\" : c == '\n' ? "\\n"
                             : c == '\t' ? "\\t" : NULL;
        char hex[5];
        if (c >= 0x80 && escape == NULL) {
            size_t length = utf8_sequence((const unsigned char *)bytes + k, n - k);
            if (length > 0) {
                run += length;
                k += length - 1;
                continue;
            }
        }
        if (escape == NULL && (c < 0x20 || c >= 0x7f)) {
            snprintf(hex, sizeof hex, "\\x%02x", c);
            escape = hex;
        }
        if (escape != NULL) {
            append(b, bytes + k - run, run);
            run = 0;
            append_text(b, escape);
        } else {
            ++run;
        }
    }
    append(b, bytes + n - run, run);
    append(b, "\"", 1);
}

char *ssx_plan_write(const ssx_plan *plan, size_t *size)
{
    if (plan == NULL) {
        return NULL;
    }
    text_buffer b = {0};
    append_text(&b, "syssimx-plan 1\n");
    for (size_t r = 0; r < plan->n_records; ++r) {
        append_text(&b, plan_schema[plan->kind[r]].keyword);
        for (size_t k = 0; k < plan->n_values[r]; ++k) {
            const plan_value *v = &plan->values[plan->first_value[r] + k];
            char number[32];
            append(&b, " ", 1);
            switch (v->kind) {
            case PLAN_INTEGER:
                snprintf(number, sizeof number, "%lld", (long long)v->as.integer);
                append_text(&b, number);
                break;
            case PLAN_DOUBLE:
                append_double(&b, v->as.real);
                break;
            case PLAN_STRING:
                append_string(&b, plan->pool + v->as.text.offset, v->as.text.size);
                break;
            default:
                append_text(&b, plan_words(v->word_set)[v->as.integer]);
                break;
            }
        }
        append(&b, "\n", 1);
    }
    if (b.failed) {
        free(b.text);
        return NULL;
    }
    if (size != NULL) {
        *size = b.size;
    }
    return b.text;
}

void ssx_plan_text_free(char *text)
{
    free(text);
}
