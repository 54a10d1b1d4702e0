/* Bytes in order (byte_stream.h). Values are written in the machine's own byte order: a state
 * is read back by the same engine build (its interface digest says so). */
#include "byte_stream.h"

#include <string.h>

#include "array.h"

unsigned char *write_room(byte_writer *w, size_t n)
{
    if (w->failed || n > SIZE_MAX - w->size ||
        array_reserve((void **)&w->bytes, &w->capacity, w->size + n, 1, 256) != 0) {
        w->failed = 1;
        return NULL;
    }
    unsigned char *room = w->bytes + w->size;
    w->size += n;
    return room;
}

void write_bytes(byte_writer *w, const void *data, size_t n)
{
    unsigned char *room = write_room(w, n);
    if (room != NULL && n > 0) {
        memcpy(room, data, n);
    }
}

void write_u64(byte_writer *w, uint64_t value)
{
    write_bytes(w, &value, sizeof value);
}

void write_doubles(byte_writer *w, const double *values, size_t n)
{
    write_bytes(w, values, n * sizeof(double));
}

const unsigned char *read_span(byte_reader *r, size_t n)
{
    if (r->failed || n > r->size - r->at) {
        r->failed = 1;
        return NULL;
    }
    const unsigned char *span = r->bytes + r->at;
    r->at += n;
    return span;
}

void read_bytes(byte_reader *r, void *data, size_t n)
{
    const unsigned char *span = read_span(r, n);
    if (span != NULL && n > 0) {
        memcpy(data, span, n);
    } else if (n > 0) {
        memset(data, 0, n);
    }
}

uint64_t read_u64(byte_reader *r)
{
    uint64_t value;
    read_bytes(r, &value, sizeof value);
    return value;
}

void read_doubles(byte_reader *r, double *values, size_t n)
{
    if (n > SIZE_MAX / sizeof(double)) {
        r->failed = 1;
        return;
    }
    read_bytes(r, values, n * sizeof(double));
}
