/* A text table: an array of copies and a hash index over it (FNV-1a, linear probing). */
#include "text_table.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint64_t hash(const char *text)
{
    uint64_t h = 14695981039346656037u;
    for (const unsigned char *p = (const unsigned char *)text; *p != '\0'; ++p) {
        h = (h ^ *p) * 1099511628211u;
    }
    return h;
}

/* The slot that holds `text`, or the empty slot where it belongs. */
static size_t find(const text_table *table, const char *text)
{
    size_t mask = table->n_slots - 1;
    size_t slot = (size_t)hash(text) & mask;
    while (table->slots[slot] != 0 && strcmp(table->texts[table->slots[slot] - 1], text) != 0) {
        slot = (slot + 1) & mask;
    }
    return slot;
}

static int grow_index(text_table *table)
{
    size_t n_slots = table->n_slots == 0 ? 16 : table->n_slots * 2;
    size_t *slots = calloc(n_slots, sizeof *slots);
    if (slots == NULL) {
        return -1;
    }
    free(table->slots);
    table->slots = slots;
    table->n_slots = n_slots;
    for (size_t k = 0; k < table->count; ++k) {
        table->slots[find(table, table->texts[k])] = k + 1;
    }
    return 0;
}

static void lock(text_table *table)
{
    while (atomic_flag_test_and_set_explicit(&table->lock, memory_order_acquire)) {
    }
}

static void unlock(text_table *table)
{
    atomic_flag_clear_explicit(&table->lock, memory_order_release);
}

static int add(text_table *table, const char *text, double *number)
{
    if (2 * (table->count + 1) > table->n_slots && grow_index(table) != 0) {
        return -1;
    }
    size_t slot = find(table, text);
    if (table->slots[slot] == 0) {
        if (table->count == table->capacity) {
            size_t capacity = table->capacity == 0 ? 8 : 2 * table->capacity;
            char **texts = realloc(table->texts, capacity * sizeof *texts);
            if (texts == NULL) {
                return -1;
            }
            table->texts = texts;
            table->capacity = capacity;
        }
        size_t size = strlen(text) + 1;
        char *copy = malloc(size);
        if (copy == NULL) {
            return -1;
        }
        memcpy(copy, text, size);
        table->texts[table->count++] = copy;
        table->slots[slot] = table->count;
    }
    *number = (double)(table->slots[slot] - 1);
    return 0;
}

int text_table_number(text_table *table, const char *text, double *number)
{
    lock(table);
    /* an FMU that returns no text returns the empty one */
    int result = add(table, text != NULL ? text : "", number);
    unlock(table);
    return result;
}

const char *text_table_text(text_table *table, double number)
{
    lock(table);
    const char *text = number >= 0.0 && number < (double)table->count &&
                               number == floor(number)
                           ? table->texts[(size_t)number]
                           : NULL;
    unlock(table);
    return text;
}

size_t text_table_count(text_table *table)
{
    lock(table);
    size_t count = table->count;
    unlock(table);
    return count;
}

void text_table_free(text_table *table)
{
    for (size_t k = 0; k < table->count; ++k) {
        free(table->texts[k]);
    }
    free(table->texts);
    free(table->slots);
    table->texts = NULL;
    table->slots = NULL;
    table->count = table->capacity = table->n_slots = 0;
}
