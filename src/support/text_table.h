/* The texts of a system's String ports: each distinct text once, numbered in the order first
 * seen. A String port's double holds its text's number, so connections, snapshots and the
 * history move numbers like any other port's; numbers stay valid until the table is freed. */
#ifndef SSX_TEXT_TABLE_H
#define SSX_TEXT_TABLE_H

#include <stdatomic.h>
#include <stddef.h>

/* Zeroed is empty. Components on several threads read and add texts: a lock guards each use
 * (held for a lookup only; the texts themselves never move). */
typedef struct {
    atomic_flag lock;
    char **texts;      /* by number */
    size_t count;
    size_t capacity;
    size_t *slots;     /* open addressing on the texts' hashes: number + 1, 0 for empty */
    size_t n_slots;    /* a power of two, at least twice count */
} text_table;

/* The number of `text` (added when new) in *number; -1 when out of memory. */
int text_table_number(text_table *table, const char *text, double *number);
/* The text numbered `number`, NULL when no text has that number. */
const char *text_table_text(text_table *table, double number);
size_t text_table_count(text_table *table);
void text_table_free(text_table *table);

#endif
