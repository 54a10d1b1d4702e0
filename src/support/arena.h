/* Memory handed out in order and given back all at once: blocks of different sizes that live as
 * long as their owner (a system's components) lie side by side in the order they were made,
 * not between whatever else was allocated in the meantime. Chunks double from 16 KiB up to
 * 2 MiB; a 2 MiB chunk is aligned to, and asked for as, one large page (Linux), so thousands of
 * blocks are reached through a few address translations. */
#ifndef SSX_ARENA_H
#define SSX_ARENA_H

#include <stddef.h>

typedef struct arena_chunk arena_chunk;

typedef struct {
    arena_chunk *chunks; /* newest first */
    char *next;          /* the newest chunk's free bytes, from here */
    size_t left;
    size_t next_chunk_bytes;
} arena;

/* An empty arena (all zero is one too). */
#define ARENA_EMPTY ((arena){0})

/* `size` zeroed bytes aligned to `alignment` (a power of two, at most 64), NULL when out of
 * memory. A block is never freed alone. */
void *arena_allocate(arena *a, size_t size, size_t alignment);
/* An empty arena's first chunk is made for about `bytes` of blocks: one 2 MiB large page or
 * more where they need that much, not a 16 KiB chunk doubling up to it. */
void arena_expect(arena *a, size_t bytes);
/* Frees every block; the arena is empty again. */
void arena_free(arena *a);

#endif
