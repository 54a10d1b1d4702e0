/* Memory handed out in order, given back all at once (see arena.h). */
#include "arena.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "large_buffer.h"
#include "poison.h"
#include "round_up.h"

/* Each chunk starts with its link, padded to a cache line so that blocks start on one. */
enum { CHUNK_HEADER = 64, FIRST_CHUNK_BYTES = 16 * 1024, MAX_ALIGNMENT = 64 };

struct arena_chunk {
    arena_chunk *next;
};

/* A new chunk holding at least `size` bytes after its header; what the old one had left is
 * not used. */
static int grow(arena *a, size_t size)
{
    size_t bytes = a->next_chunk_bytes != 0 ? a->next_chunk_bytes : FIRST_CHUNK_BYTES;
    while (bytes < CHUNK_HEADER + size) {
        bytes *= 2;
    }
    size_t alignment = bytes >= LARGE_PAGE_BYTES ? LARGE_PAGE_BYTES : MAX_ALIGNMENT;
    bytes = round_up(bytes, alignment);
    arena_chunk *chunk = large_buffer_chunk(bytes, alignment);
    if (chunk == NULL) {
        return -1;
    }
    chunk->next = a->chunks;
    a->chunks = chunk;
    a->next = (char *)chunk + CHUNK_HEADER;
    a->left = bytes - CHUNK_HEADER;
    POISON(a->next, a->left);
    a->next_chunk_bytes = bytes < LARGE_PAGE_BYTES ? 2 * bytes : LARGE_PAGE_BYTES;
    return 0;
}

void *arena_allocate(arena *a, size_t size, size_t alignment)
{
    if (alignment == 0 || (alignment & (alignment - 1)) != 0 || alignment > MAX_ALIGNMENT) {
        return NULL;
    }
    size_t needed = size + POISON_REDZONE;
    size_t pad = a->next != NULL ? (alignment - (uintptr_t)a->next % alignment) % alignment : 0;
    if (a->next == NULL || pad + needed > a->left) {
        if (grow(a, needed) != 0) {
            return NULL;
        }
        pad = 0; /* a chunk's blocks start on a cache line */
    }
    char *block = a->next + pad;
    a->next = block + needed;
    a->left -= pad + needed;
    UNPOISON(block, size);
    memset(block, 0, size);
    return block;
}

void arena_expect(arena *a, size_t bytes)
{
    if (a->chunks != NULL) {
        return;
    }
    size_t chunk = FIRST_CHUNK_BYTES;
    while (chunk < LARGE_PAGE_BYTES && chunk < CHUNK_HEADER + bytes) {
        chunk *= 2;
    }
    a->next_chunk_bytes = chunk;
}

void arena_free(arena *a)
{
    while (a->chunks != NULL) {
        arena_chunk *chunk = a->chunks;
        a->chunks = chunk->next;
        free(chunk);
    }
    *a = ARENA_EMPTY;
}
