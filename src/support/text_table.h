/* The values of a system's String and Binary ports: each distinct value once, numbered in the
 * order first seen. Such a port's double holds its value's number, so connections, snapshots
 * and the history move numbers like any other port's; numbers stay valid until the table is
 * freed. A value is bytes with a size; each copy ends in a NUL, so a text reads as a string. */
#ifndef SSX_TEXT_TABLE_H
#define SSX_TEXT_TABLE_H

#include <stdatomic.h>
#include <stddef.h>

/* Zeroed is empty. Components on several threads read and add values: a lock guards each use
 * (held for a lookup only; the values themselves never move). */
typedef struct {
    atomic_flag lock;
    unsigned char **values; /* by number */
    size_t *sizes;
    size_t count;
    size_t capacity;
    size_t *slots;  /* open addressing on the values' hashes: number + 1, 0 for empty */
    size_t n_slots; /* a power of two, at least twice count */
} text_table;

/* The number of the `size` bytes at `data` (added when new) in *number; -1 when out of
 * memory. NULL data is the empty value. */
int text_table_bytes_number(text_table *table, const void *data, size_t size, double *number);
/* The same for a text (its bytes up to the NUL; NULL: the empty text). */
int text_table_number(text_table *table, const char *text, double *number);
/* The value numbered `number` and its size in *size, NULL when no value has that number. */
const unsigned char *text_table_bytes(text_table *table, double number, size_t *size);
/* The value numbered `number` as a text, NULL when no value has that number. */
const char *text_table_text(text_table *table, double number);
size_t text_table_count(text_table *table);
void text_table_free(text_table *table);

#endif
