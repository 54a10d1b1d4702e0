#include "array.h"

#include <stdlib.h>

int array_reserve(void **array, size_t *capacity, size_t needed, size_t element_size,
                  size_t initial)
{
    if (needed <= *capacity) {
        return 0;
    }
    size_t grown_capacity = *capacity > 0 ? 2 * *capacity : initial;
    while (grown_capacity < needed) {
        grown_capacity *= 2;
    }
    void *grown = realloc(*array, grown_capacity * element_size);
    if (grown == NULL) {
        return -1;
    }
    *array = grown;
    *capacity = grown_capacity;
    return 0;
}
