/* Bytes written and read in order: what a serialized state is made of. A writer grows its
 * buffer by array.h's rule; a reader never reads past its end. Both remember a failure, so a
 * sequence of calls is checked once at its end. */
#ifndef SSX_BYTE_STREAM_H
#define SSX_BYTE_STREAM_H

#include <stddef.h>
#include <stdint.h>

typedef struct byte_writer {
    unsigned char *bytes; /* malloc'd, the caller's once written */
    size_t size;
    size_t capacity;
    int failed; /* out of memory */
} byte_writer;

typedef struct byte_reader {
    const unsigned char *bytes;
    size_t size;
    size_t at;
    int failed; /* a read past the end */
} byte_reader;

void write_bytes(byte_writer *w, const void *data, size_t n);
void write_u64(byte_writer *w, uint64_t value);
void write_doubles(byte_writer *w, const double *values, size_t n);
/* Room for n bytes at the end, to be filled by the caller; NULL when out of memory. */
unsigned char *write_room(byte_writer *w, size_t n);

void read_bytes(byte_reader *r, void *data, size_t n);
uint64_t read_u64(byte_reader *r);
void read_doubles(byte_reader *r, double *values, size_t n);
/* The next n bytes, skipped; NULL when fewer are left. */
const unsigned char *read_span(byte_reader *r, size_t n);

#endif
