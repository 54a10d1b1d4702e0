/* The string pool and the name index (see string_store.h). */
#include "string_store.h"

#include <stdlib.h>
#include <string.h>

#include "array.h"

bool string_pool_start(string_pool *pool, size_t capacity)
{
    pool->text = malloc(capacity);
    if (pool->text == NULL) {
        return false;
    }
    pool->text[0] = '\0'; /* offset 0 means absent */
    pool->size = 1;
    pool->capacity = capacity;
    return true;
}

bool string_pool_add(string_pool *pool, slice text, uint32_t *offset)
{
    if (text.at == NULL) {
        *offset = 0;
        return true;
    }
    /* decoding never lengthens a text */
    if (array_reserve((void **)&pool->text, &pool->capacity, pool->size + text.length + 1, 1,
                      4096)) {
        return false;
    }
    char *out = pool->text + pool->size;
    size_t length = text.plain ? (memcpy(out, text.at, text.length), text.length)
                               : xml_decode(out, text);
    out[length] = '\0';
    *offset = (uint32_t)pool->size;
    pool->size += length + 1;
    return true;
}

/* FNV-1a: names of generated models differ in few characters, and it mixes each of them. */
static uint32_t hash_of(const char *key)
{
    uint32_t hash = 2166136261u;
    for (const unsigned char *p = (const unsigned char *)key; *p != '\0'; ++p) {
        hash = (hash ^ *p) * 16777619u;
    }
    return hash;
}

int64_t name_index_find(const ssx_md_names *names, const char *pool, const char *key)
{
    if (names == NULL || names->slots == NULL) {
        return -1;
    }
    uint32_t hash = hash_of(key);
    for (size_t i = hash & names->mask;; i = (i + 1) & names->mask) {
        const ssx_md_slot *slot = &names->slots[i];
        if (slot->item == 0) {
            return -1;
        }
        if (slot->hash == hash && strcmp(pool + slot->key, key) == 0) {
            return (int64_t)slot->item - 1;
        }
    }
}

static bool name_index_grow(ssx_md_names *names)
{
    size_t capacity = names->slots != NULL ? 2 * (names->mask + 1) : 1024;
    ssx_md_slot *slots = calloc(capacity, sizeof *slots);
    if (slots == NULL) {
        return false;
    }
    for (size_t i = 0; names->slots != NULL && i <= names->mask; ++i) {
        ssx_md_slot slot = names->slots[i];
        if (slot.item != 0) {
            size_t j = slot.hash & (capacity - 1);
            while (slots[j].item != 0) {
                j = (j + 1) & (capacity - 1);
            }
            slots[j] = slot;
        }
    }
    free(names->slots);
    names->slots = slots;
    names->mask = capacity - 1;
    return true;
}

int64_t name_index_put(ssx_md_names *names, const char *pool, uint32_t key, uint32_t item,
                       bool replace)
{
    if ((names->slots == NULL || 2 * (names->count + 1) > names->mask + 1) &&
        !name_index_grow(names)) {
        return -2;
    }
    uint32_t hash = hash_of(pool + key);
    for (size_t i = hash & names->mask;; i = (i + 1) & names->mask) {
        ssx_md_slot *slot = &names->slots[i];
        if (slot->item == 0) {
            *slot = (ssx_md_slot){item + 1, key, hash};
            ++names->count;
            return -1;
        }
        if (slot->hash == hash && strcmp(pool + slot->key, pool + key) == 0) {
            int64_t previous = (int64_t)slot->item - 1;
            if (replace) {
                *slot = (ssx_md_slot){item + 1, key, hash};
            }
            return previous;
        }
    }
}

void name_index_free(ssx_md_names *names)
{
    if (names != NULL) {
        free(names->slots);
    }
}
