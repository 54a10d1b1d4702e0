/* Formatting what an FMU logs: conversions one at a time, none read through a pointer. */
#include "fmu_message.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* What one conversion's argument is read as: its length modifier decides the C type. */
typedef enum { READ_NOTHING, READ_INT, READ_LONG, READ_LONG_LONG, READ_SIZE, READ_INTMAX,
               READ_PTRDIFF, READ_DOUBLE, READ_LONG_DOUBLE, READ_POINTER } argument_kind;

typedef struct {
    char *out;
    size_t size;
    size_t used; /* characters written, less than size */
} message_buffer;

static void append(message_buffer *b, const char *text, size_t length)
{
    size_t room = b->size - 1 - b->used;
    length = length < room ? length : room;
    memcpy(b->out + b->used, text, length);
    b->used += length;
    b->out[b->used] = '\0';
}

static argument_kind kind_of(char conversion, const char *length)
{
    if (strchr("diouxXc", conversion) != NULL) {
        if (conversion == 'c' && length[0] != '\0') {
            return READ_NOTHING; /* %lc: a wide character, left as written */
        }
        if (length[0] == 'l') {
            return length[1] == 'l' ? READ_LONG_LONG : READ_LONG;
        }
        switch (length[0]) {
        case 'q':
            return READ_LONG_LONG;
        case 'z':
            return READ_SIZE;
        case 'j':
            return READ_INTMAX;
        case 't':
            return READ_PTRDIFF;
        default:
            return READ_INT; /* hh and h are promoted to int */
        }
    }
    if (strchr("eEfFgGaA", conversion) != NULL) {
        return length[0] == 'L' ? READ_LONG_DOUBLE : READ_DOUBLE;
    }
    return conversion == 'p' ? READ_POINTER : READ_NOTHING;
}

/* The conversion `spec` (from '%' to its letter, NUL-terminated) with its argument. */
static int format_one(char *piece, size_t size, const char *spec, argument_kind kind,
                      va_list *args)
{
    switch (kind) {
    case READ_INT:
        return snprintf(piece, size, spec, va_arg(*args, int));
    case READ_LONG:
        return snprintf(piece, size, spec, va_arg(*args, long));
    case READ_LONG_LONG:
        return snprintf(piece, size, spec, va_arg(*args, long long));
    case READ_SIZE:
        return snprintf(piece, size, spec, va_arg(*args, size_t));
    case READ_INTMAX:
        return snprintf(piece, size, spec, va_arg(*args, intmax_t));
    case READ_PTRDIFF:
        return snprintf(piece, size, spec, va_arg(*args, ptrdiff_t));
    case READ_DOUBLE:
        return snprintf(piece, size, spec, va_arg(*args, double));
    case READ_LONG_DOUBLE:
        return snprintf(piece, size, spec, va_arg(*args, long double));
    case READ_POINTER:
        return snprintf(piece, size, spec, va_arg(*args, void *));
    case READ_NOTHING:
        break;
    }
    return -1;
}

void ssx_format_fmu_message(char *out, size_t size, const char *format, va_list args)
{
    if (size == 0) {
        return;
    }
    message_buffer b = {out, size, 0};
    out[0] = '\0';
    if (format == NULL) {
        return;
    }
    va_list rest;
    va_copy(rest, args);
    int reads_left = SSX_FMU_MESSAGE_MAX_ARGUMENTS;
    const char *p = format;
    while (*p != '\0') {
        const char *percent = strchr(p, '%');
        if (percent == NULL) {
            append(&b, p, strlen(p));
            break;
        }
        append(&b, p, (size_t)(percent - p));
        if (percent[1] == '%') {
            append(&b, "%", 1);
            p = percent + 2;
            continue;
        }
        /* flags, width, precision, length modifier, conversion letter */
        const char *q = percent + 1 + strspn(percent + 1, "-+ #0'");
        q += strspn(q, "0123456789.");
        size_t length_size = strspn(q, "hlLqjzt");
        char length[3] = "";
        memcpy(length, q, length_size < 2 ? length_size : 2);
        const char *letter = q + length_size;
        size_t spec_size = (size_t)(letter - percent) + (*letter != '\0');
        p = percent + spec_size;
        argument_kind kind = *letter != '\0' ? kind_of(*letter, length) : READ_NOTHING;
        if (reads_left > 0 && *letter == 's') {
            /* the pointer is skipped by value, never read through: the text stays */
            (void)va_arg(rest, void *);
            --reads_left;
            append(&b, percent, spec_size);
            continue;
        }
        char spec[32];
        if (kind == READ_NOTHING || reads_left == 0 || length_size > 2 ||
            spec_size >= sizeof spec) {
            /* kept as written ('*', "%n", an unknown letter); what it would read is unknown,
             * so nothing after it is read either */
            reads_left = 0;
            append(&b, percent, spec_size);
            continue;
        }
        memcpy(spec, percent, spec_size);
        spec[spec_size] = '\0';
        --reads_left;
        char piece[256];
        if (format_one(piece, sizeof piece, spec, kind, &rest) > 0) {
            append(&b, piece, strlen(piece));
        }
    }
    va_end(rest);
}
