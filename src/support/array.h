/* Growable arrays: the one doubling rule every engine buffer of unknown final size follows. */
#ifndef SYSSIMX_ARRAY_H
#define SYSSIMX_ARRAY_H

#include <stddef.h>

/* Makes *array hold at least `needed` elements of element_size bytes, doubling its capacity
 * (from `initial` when empty). Returns 0, or -1 with *array and *capacity unchanged. */
int array_reserve(void **array, size_t *capacity, size_t needed, size_t element_size,
                  size_t initial);

#endif
