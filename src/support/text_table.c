/* A text table: an array of copies and a hash index over it (FNV-1a, linear probing). */
#include "text_table.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint64_t hash(const unsigned char *data, size_t size)
{
    uint64_t h = 14695981039346656037u;
    for (size_t k = 0; k < size; ++k) {
        h = (h ^ data[k]) * 1099511628211u;
    }
    return h;
}

static int holds(const text_table *table, size_t number, const unsigned char *data, size_t size)
{
    return table->sizes[number] == size && (size == 0 || memcmp(table->values[number], data,
                                                                 size) == 0);
}

/* The slot that holds the value, or the empty slot where it belongs. */
static size_t find(const text_table *table, const unsigned char *data, size_t size)
{
    size_t mask = table->n_slots - 1;
    size_t slot = (size_t)hash(data, size) & mask;
    while (table->slots[slot] != 0 && !holds(table, table->slots[slot] - 1, data, size)) {
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
        table->slots[find(table, table->values[k], table->sizes[k])] = k + 1;
    }
    return 0;
}

static int grow_values(text_table *table)
{
    size_t capacity = table->capacity == 0 ? 8 : 2 * table->capacity;
    unsigned char **values = realloc(table->values, capacity * sizeof *values);
    if (values != NULL) {
        table->values = values;
    }
    size_t *sizes = realloc(table->sizes, capacity * sizeof *sizes);
    if (sizes != NULL) {
        table->sizes = sizes;
    }
    if (values == NULL || sizes == NULL) {
        return -1;
    }
    table->capacity = capacity;
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

static int add(text_table *table, const unsigned char *data, size_t size, double *number)
{
    if (2 * (table->count + 1) > table->n_slots && grow_index(table) != 0) {
        return -1;
    }
    size_t slot = find(table, data, size);
    if (table->slots[slot] == 0) {
        if (table->count == table->capacity && grow_values(table) != 0) {
            return -1;
        }
        unsigned char *copy = malloc(size + 1);
        if (copy == NULL) {
            return -1;
        }
        if (size > 0) {
            memcpy(copy, data, size);
        }
        copy[size] = '\0';
        table->values[table->count] = copy;
        table->sizes[table->count] = size;
        table->slots[slot] = ++table->count;
    }
    *number = (double)(table->slots[slot] - 1);
    return 0;
}

int text_table_bytes_number(text_table *table, const void *data, size_t size, double *number)
{
    static const unsigned char empty[1] = {0};
    lock(table);
    int result = add(table, data != NULL ? data : empty, data != NULL ? size : 0, number);
    unlock(table);
    return result;
}

int text_table_number(text_table *table, const char *text, double *number)
{
    /* an FMU that returns no text returns the empty one */
    return text_table_bytes_number(table, text, text != NULL ? strlen(text) : 0, number);
}

const unsigned char *text_table_bytes(text_table *table, double number, size_t *size)
{
    lock(table);
    int known = number >= 0.0 && number < (double)table->count && number == floor(number);
    const unsigned char *value = known ? table->values[(size_t)number] : NULL;
    *size = known ? table->sizes[(size_t)number] : 0;
    unlock(table);
    return value;
}

const char *text_table_text(text_table *table, double number)
{
    size_t size;
    return (const char *)text_table_bytes(table, number, &size);
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
        free(table->values[k]);
    }
    free(table->values);
    free(table->sizes);
    free(table->slots);
    table->values = NULL;
    table->sizes = NULL;
    table->slots = NULL;
    table->count = table->capacity = table->n_slots = 0;
}
