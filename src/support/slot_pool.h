/* Slots of one size, handed out next to each other: where thousands of objects are made one
 * after the other and each is read once per step (the FMU bindings of a large system), they
 * then fill a few pages in the order they were made, instead of lying between whatever else
 * was allocated in the meantime.
 *
 * The pool grows by chunks (each twice the slots of the one before, up to a limit) and never
 * moves a slot. A slot given back is reused by the next take. The pool is reference-counted:
 * its maker holds one reference and every slot taken holds one, so the pool and its chunks go
 * when the maker has released it and the last slot is given back, in either order, from any
 * thread. */
#ifndef SSX_SLOT_POOL_H
#define SSX_SLOT_POOL_H

#include <stddef.h>

typedef struct slot_pool slot_pool;

/* A pool of slots of `size` bytes, each aligned to `alignment` (a power of two, at most 4096);
 * NULL when out of memory. */
slot_pool *slot_pool_new(size_t size, size_t alignment);
/* A zeroed slot, NULL when out of memory. */
void *slot_pool_take(slot_pool *pool);
/* Gives back a slot taken from this pool. Never waits: when another thread holds the pool at
 * that moment, the slot is not reused but still freed with the pool. */
void slot_pool_give_back(slot_pool *pool, void *slot);
/* The maker's reference; the pool goes when no slot is left taken. */
void slot_pool_release(slot_pool *pool);
/* Slots taken and not given back. */
size_t slot_pool_in_use(slot_pool *pool);

#endif
