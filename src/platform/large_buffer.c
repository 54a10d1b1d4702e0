/* Large buffers (see large_buffer.h). */
#define _GNU_SOURCE /* mremap */

#include "large_buffer.h"

#include <stdlib.h>
#include <string.h>

#if defined(__linux__)
#include <sys/mman.h>

/* Buffers from this size on are pages of their own. */
static const size_t MAPPED_MIN_BYTES = 1024 * 1024;

static int is_mapped(size_t bytes)
{
    return bytes >= MAPPED_MIN_BYTES;
}

void large_buffer_free(void *data, size_t bytes)
{
    if (data != NULL && is_mapped(bytes)) {
        munmap(data, bytes);
    } else {
        free(data);
    }
}

void *large_buffer_allocate(size_t bytes)
{
    if (!is_mapped(bytes)) {
        return malloc(bytes);
    }
    void *data = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (data == MAP_FAILED) {
        return NULL;
    }
    if (bytes >= LARGE_PAGE_BYTES) {
        /* a hint, kept by mremap: its 2 MiB-aligned stretches may be large pages */
        (void)madvise(data, bytes, MADV_HUGEPAGE);
    }
    return data;
}

void *large_buffer_resize(void *data, size_t bytes, size_t new_bytes)
{
    if (is_mapped(bytes) && is_mapped(new_bytes)) {
        void *moved = mremap(data, bytes, new_bytes, MREMAP_MAYMOVE);
        return moved != MAP_FAILED ? moved : NULL;
    }
    if (!is_mapped(bytes) && !is_mapped(new_bytes)) {
        return realloc(data, new_bytes);
    }
    /* crossing the threshold: the other kind of allocation */
    void *other = large_buffer_allocate(new_bytes);
    if (other != NULL) {
        memcpy(other, data, new_bytes < bytes ? new_bytes : bytes);
        large_buffer_free(data, bytes);
    }
    return other;
}

void *large_buffer_chunk(size_t bytes, size_t alignment)
{
    void *chunk = aligned_alloc(alignment, bytes);
    if (chunk != NULL && alignment >= LARGE_PAGE_BYTES) {
        (void)madvise(chunk, bytes, MADV_HUGEPAGE);
    }
    return chunk;
}

#else

void *large_buffer_chunk(size_t bytes, size_t alignment)
{
    return aligned_alloc(alignment, bytes);
}

void large_buffer_free(void *data, size_t bytes)
{
    (void)bytes;
    free(data);
}

void *large_buffer_allocate(size_t bytes)
{
    return malloc(bytes);
}

void *large_buffer_resize(void *data, size_t bytes, size_t new_bytes)
{
    (void)bytes;
    return realloc(data, new_bytes);
}

#endif
