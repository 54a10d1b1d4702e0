/* Writing a plan: the header, then each record as its keyword and values, following its
 * signature (plan_schema.c). A double is written in the fewest digits (15, 16 or 17) that read
 * back to the same double, a list of more than PLAN_DECIMAL_DOUBLES_MAX doubles in its hex
 * form, so that reading what was written and writing it again gives the same text; a string
 * stays UTF-8 text. */
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

static void append_value(text_buffer *b, const ssx_plan *plan, const plan_value *v)
{
    char number[32];
    append(b, " ", 1);
    switch (v->kind) {
    case PLAN_INTEGER:
        snprintf(number, sizeof number, "%lld", (long long)v->as.integer);
        append_text(b, number);
        break;
    case PLAN_DOUBLE:
        append_double(b, v->as.real);
        break;
    case PLAN_STRING:
        append_string(b, plan->pool + v->as.text.offset, v->as.text.size);
        break;
    default:
        append_text(b, plan_words(v->word_set)[v->as.integer]);
        break;
    }
}

/* A list of doubles in its hex form: `xN:`, then each value's IEEE-754 binary64 bytes, least
 * significant first, as 16 lowercase hex digits: exact (NaN payloads too) and no formatting. */
static void append_hex_doubles(text_buffer *b, const plan_value *values, size_t count)
{
    static const char digits[] = "0123456789abcdef";
    char head[32];
    snprintf(head, sizeof head, " x%zu:", count);
    append_text(b, head);
    for (size_t k = 0; k < count; ++k) {
        uint64_t bits;
        memcpy(&bits, &values[k].as.real, sizeof bits);
        char hex[16];
        for (int byte = 0; byte < 8; ++byte) {
            unsigned int octet = (unsigned int)(bits >> (8 * byte)) & 0xffu;
            hex[2 * byte] = digits[octet >> 4];
            hex[2 * byte + 1] = digits[octet & 0xfu];
        }
        append(b, hex, sizeof hex);
    }
}

/* The values of `signature` (plan_schema.c) from values[0]; the number of values written. */
static size_t append_signature(text_buffer *b, const ssx_plan *plan, const plan_value *values,
                               const char *signature, size_t length)
{
    size_t used = 0;
    for (size_t k = 0; k < length; ++k) {
        if (signature[k] == 'g') { /* a schedule group: its size, its flag, its members */
            size_t members = (size_t)values[used].as.integer;
            for (size_t m = 0; m < members + 2; ++m) {
                append_value(b, plan, &values[used++]);
            }
        } else if (signature[k] == '[') {
            const char *close = strchr(signature + k, ']');
            size_t inner = (size_t)(close - signature) - k - 1;
            size_t count = (size_t)values[used].as.integer;
            if (inner == 1 && signature[k + 1] == 'd' && count > PLAN_DECIMAL_DOUBLES_MAX) {
                append_hex_doubles(b, &values[used + 1], count);
                used += 1 + count;
            } else {
                append_value(b, plan, &values[used++]);
                for (size_t item = 0; item < count; ++item) {
                    used += append_signature(b, plan, &values[used], signature + k + 1, inner);
                }
            }
            k += inner + 1;
        } else {
            append_value(b, plan, &values[used++]);
        }
    }
    return used;
}

char *ssx_plan_write(const ssx_plan *plan, size_t *size)
{
    if (plan == NULL) {
        return NULL;
    }
    text_buffer b = {0};
    append_text(&b, "syssimx-plan 1\n");
    for (size_t r = 0; r < plan->n_records; ++r) {
        const char *signature = plan_schema[plan->kind[r]].signature;
        append_text(&b, plan_schema[plan->kind[r]].keyword);
        append_signature(&b, plan, &plan->values[plan->first_value[r]], signature,
                         strlen(signature));
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
