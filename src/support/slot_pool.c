/* Slots of one size, next to each other (see slot_pool.h). */
#include "slot_pool.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "large_buffer.h"
#include "poison.h"
#include "round_up.h"

/* The first chunk's slots, and the most a chunk holds: a system of ten FMUs takes one small
 * chunk, one of ten thousand a few large ones. */
enum { FIRST_CHUNK_SLOTS = 16, MAX_CHUNK_SLOTS = 4096 };
typedef struct chunk {
    struct chunk *next;
} chunk;

struct slot_pool {
    pthread_mutex_t lock;
    atomic_size_t references; /* the maker's and one per slot taken */
    atomic_size_t in_use;
    size_t size;      /* a slot's stride: its size rounded up to the alignment */
    size_t alignment;
    size_t header;    /* a chunk's header rounded up to the alignment */
    chunk *chunks;    /* newest first */
    size_t next_chunk_slots;
    char *fresh;      /* the newest chunk's slots never taken, from here */
    size_t fresh_left;
    void *given_back; /* slots given back, each holding the next one's address */
};

slot_pool *slot_pool_new(size_t size, size_t alignment)
{
    if (alignment == 0 || (alignment & (alignment - 1)) != 0 || alignment > 4096) {
        return NULL;
    }
    slot_pool *pool = calloc(1, sizeof *pool);
    if (pool == NULL) {
        return NULL;
    }
    if (pthread_mutex_init(&pool->lock, NULL) != 0) {
        free(pool);
        return NULL;
    }
    atomic_init(&pool->references, 1);
    atomic_init(&pool->in_use, 0);
    /* a slot given back holds a pointer */
    pool->size = round_up(size > sizeof(void *) ? size : sizeof(void *), alignment);
    pool->alignment = alignment;
    pool->header = round_up(sizeof(chunk), alignment);
    pool->next_chunk_slots = FIRST_CHUNK_SLOTS;
    return pool;
}

/* A new chunk for the fresh slots (the old chunk's fresh ones, if any, are left unused). One
 * that would reach a large page is one large page, filled with as many slots as it holds. */
static int grow(slot_pool *pool)
{
    size_t slots = pool->next_chunk_slots;
    size_t bytes = pool->header + slots * pool->size;
    size_t alignment = pool->alignment;
    if (bytes >= LARGE_PAGE_BYTES && pool->header + pool->size <= LARGE_PAGE_BYTES) {
        slots = (LARGE_PAGE_BYTES - pool->header) / pool->size;
        bytes = LARGE_PAGE_BYTES;
        alignment = LARGE_PAGE_BYTES;
    }
    chunk *c = large_buffer_chunk(round_up(bytes, alignment), alignment);
    if (c == NULL) {
        return -1;
    }
    c->next = pool->chunks;
    pool->chunks = c;
    pool->fresh = (char *)c + pool->header;
    pool->fresh_left = slots;
    POISON(pool->fresh, pool->fresh_left * pool->size);
    if (pool->next_chunk_slots < MAX_CHUNK_SLOTS) {
        pool->next_chunk_slots *= 2;
    }
    return 0;
}

void *slot_pool_take(slot_pool *pool)
{
    pthread_mutex_lock(&pool->lock);
    void *slot = pool->given_back;
    if (slot != NULL) {
        UNPOISON(slot, pool->size);
        memcpy(&pool->given_back, slot, sizeof(void *));
    } else if (pool->fresh_left > 0 || grow(pool) == 0) {
        slot = pool->fresh;
        UNPOISON(slot, pool->size);
        pool->fresh += pool->size;
        pool->fresh_left--;
    }
    pthread_mutex_unlock(&pool->lock);
    if (slot == NULL) {
        return NULL;
    }
    atomic_fetch_add(&pool->references, 1);
    atomic_fetch_add(&pool->in_use, 1);
    memset(slot, 0, pool->size);
    return slot;
}

static void destroy(slot_pool *pool)
{
    while (pool->chunks != NULL) {
        chunk *c = pool->chunks;
        pool->chunks = c->next;
        free(c);
    }
    pthread_mutex_destroy(&pool->lock);
    free(pool);
}

static void drop_reference(slot_pool *pool)
{
    if (atomic_fetch_sub(&pool->references, 1) == 1) {
        destroy(pool);
    }
}

void slot_pool_give_back(slot_pool *pool, void *slot)
{
    atomic_fetch_sub(&pool->in_use, 1);
    /* a process forked while another thread held the lock would wait here for ever */
    if (pthread_mutex_trylock(&pool->lock) == 0) {
        memcpy(slot, &pool->given_back, sizeof(void *));
        POISON(slot, pool->size);
        pool->given_back = slot;
        pthread_mutex_unlock(&pool->lock);
    } else {
        POISON(slot, pool->size);
    }
    drop_reference(pool);
}

void slot_pool_release(slot_pool *pool)
{
    if (pool != NULL) {
        drop_reference(pool);
    }
}

size_t slot_pool_in_use(slot_pool *pool)
{
    return atomic_load(&pool->in_use);
}
