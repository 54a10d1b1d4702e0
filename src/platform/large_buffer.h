/* Memory for buffers that may grow large and are resized often (the history's columns). Where
 * the system allows it (Linux), a large buffer is pages of its own: it grows and shrinks by
 * remapping, which copies nothing, and pages beyond what was written are never made resident.
 * malloc does so too above its mmap threshold, but that threshold moves with the program's
 * frees. Elsewhere these are malloc, realloc and free. */
#ifndef SSX_LARGE_BUFFER_H
#define SSX_LARGE_BUFFER_H

#include <stddef.h>

void *large_buffer_allocate(size_t bytes);
/* The buffer of `bytes` resized to `new_bytes`, its contents kept up to the smaller size; NULL,
 * with the buffer unchanged, when out of memory. */
void *large_buffer_resize(void *data, size_t bytes, size_t new_bytes);
void large_buffer_free(void *data, size_t bytes);

/* The large pages of x86-64 and AArch64 Linux: memory aligned to this size, in multiples of it,
 * can be mapped as such pages, one address translation for 2 MiB instead of 512. */
enum { LARGE_PAGE_BYTES = 2 << 20 };
/* `bytes` (a multiple of `alignment`, a power of two) aligned to `alignment`, freed with free;
 * NULL when out of memory. Aligned to LARGE_PAGE_BYTES, it is asked for as large pages where the
 * system has them (a hint: small pages serve where they are off or used up). */
void *large_buffer_chunk(size_t bytes, size_t alignment);

#endif
