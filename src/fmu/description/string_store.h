/* The reader's strings: one pool of NUL-ended texts addressed by 32-bit offsets (offset 0 is
 * the empty text, meaning absent), and an index from names in the pool to items. */
#ifndef SSX_STRING_STORE_H
#define SSX_STRING_STORE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "xml_tokenizer.h"

typedef struct {
    char *text;
    size_t size, capacity;
} string_pool;

/* An empty pool holding only the absent text, sized for about `capacity` bytes. */
bool string_pool_start(string_pool *pool, size_t capacity);
/* The text, decoded, appended to the pool: *offset is where it starts (0 when absent).
 * False when out of memory. */
bool string_pool_add(string_pool *pool, slice text, uint32_t *offset);

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

/* Enters item under the name at pool + key. If the name is there already, returns the item it
 * names (and puts item in its place when replace); -1 after entering it; -2: out of memory. */
int64_t name_index_put(ssx_md_names *names, const char *pool, uint32_t key, uint32_t item,
                       bool replace);
/* The item named key, or -1. */
int64_t name_index_find(const ssx_md_names *names, const char *pool, const char *key);
void name_index_free(ssx_md_names *names);

#endif
