/* The slot pool that FMU bindings are made in: slots side by side in the order taken, aligned,
 * zeroed, reused once given back, chunks that grow up to one large page, and a pool that
 * lives until its maker released it and its last slot came back, in either order (run under
 * AddressSanitizer, a slot used after the pool went or a chunk never freed is reported). Then
 * bindings loaded with a pool: adjacent, working, freed before and after the pool. */
#include <stdint.h>
#include <string.h>

#include "slot_pool.h"
#include "test_support.h"

enum { LINE = 64, FIRST_CHUNK = 16 };

static int zeroed(const unsigned char *slot, size_t size)
{
    for (size_t i = 0; i < size; ++i) {
        if (slot[i] != 0) {
            return 0;
        }
    }
    return 1;
}

static void slots_side_by_side(void)
{
    slot_pool *pool = slot_pool_new(40, LINE); /* a 40-byte slot takes one line */
    CHECK(pool != NULL);
    unsigned char *slots[FIRST_CHUNK + 1];
    for (int i = 0; i <= FIRST_CHUNK; ++i) {
        slots[i] = slot_pool_take(pool);
        CHECK(slots[i] != NULL);
        CHECK((uintptr_t)slots[i] % LINE == 0);
        CHECK(zeroed(slots[i], 40));
        memset(slots[i], 0xA5, 40);
    }
    for (int i = 1; i < FIRST_CHUNK; ++i) {
        CHECK(slots[i] - slots[i - 1] == LINE); /* the first chunk, in the order taken */
    }
    CHECK(slot_pool_in_use(pool) == FIRST_CHUNK + 1);

    /* the slot given back last is taken next, zeroed again */
    slot_pool_give_back(pool, slots[3]);
    CHECK(slot_pool_in_use(pool) == FIRST_CHUNK);
    unsigned char *again = slot_pool_take(pool);
    CHECK(again == slots[3]);
    CHECK(zeroed(again, 40));

    /* the maker lets go first: the slots stay usable until each is given back */
    slot_pool_release(pool);
    memset(slots[FIRST_CHUNK], 0x5A, 40);
    CHECK(slots[FIRST_CHUNK][39] == 0x5A);
    for (int i = 0; i <= FIRST_CHUNK; ++i) {
        slot_pool_give_back(pool, slots[i]);
    }
}

/* Chunks double from 16 slots; one that would reach 2 MiB is exactly 2 MiB, on a 2 MiB
 * boundary: its header line, then as many slots as fit. */
static void chunks_grow_to_large_pages(void)
{
    enum { SLOT = 640, SMALL = 16 + 32 + 64 + 128 + 256 + 512 + 1024 + 2048 };
    enum { LARGE = ((2 << 20) - LINE) / SLOT, TAKEN = SMALL + LARGE + 1 };
    slot_pool *pool = slot_pool_new(SLOT, LINE);
    CHECK(pool != NULL);
    static unsigned char *slots[TAKEN];
    for (int i = 0; i < TAKEN; ++i) {
        slots[i] = slot_pool_take(pool);
        CHECK(slots[i] != NULL);
    }
    size_t first = 0;
    for (size_t chunk = 16; first < SMALL; first += chunk, chunk *= 2) {
        for (size_t i = first + 1; i < first + chunk; ++i) {
            CHECK(slots[i] - slots[i - 1] == SLOT);
        }
    }
    CHECK(((uintptr_t)slots[SMALL] - LINE) % ((uintptr_t)2 << 20) == 0);
    for (size_t i = SMALL + 1; i < SMALL + LARGE; ++i) {
        CHECK(slots[i] - slots[i - 1] == SLOT);
    }
    /* the large chunk is full: the next slot lies in another */
    uintptr_t large = (uintptr_t)slots[SMALL], next = (uintptr_t)slots[TAKEN - 1];
    CHECK(next < large || next >= large + ((uintptr_t)2 << 20));
    CHECK(slot_pool_in_use(pool) == TAKEN);
    for (int i = TAKEN - 1; i >= 0; --i) {
        slot_pool_give_back(pool, slots[i]);
    }
    CHECK(slot_pool_in_use(pool) == 0);
    slot_pool_release(pool);
}

/* Gain: y = k * u with k = 1. */
enum { GAIN_Y = 0, GAIN_U = 1 };

static double step_gain(ssx_fmu *fmu, double u)
{
    const unsigned int in = GAIN_U, out = GAIN_Y;
    double y = -1.0;
    CHECK(ssx_fmu_set_real(fmu, &in, 1, &u) == 0);
    CHECK(ssx_fmu_do_step(fmu, 0.0, 1e-3, 1) == 0);
    CHECK(ssx_fmu_get_real(fmu, &out, 1, &y) == 0);
    return y;
}

static void bindings_in_a_pool(void)
{
    ssx_binding_pool *pool = ssx_binding_pool_new();
    CHECK(pool != NULL);
    ssx_fmu *gains[3];
    for (int i = 0; i < 3; ++i) {
        gains[i] = load_fmu_in("gain", pool);
    }
    ptrdiff_t stride = (char *)gains[1] - (char *)gains[0];
    CHECK(stride > 0 && stride % LINE == 0 && stride <= 1024); /* small, and side by side */
    CHECK((char *)gains[2] - (char *)gains[1] == stride);
    for (int i = 0; i < 3; ++i) {
        CHECK(start_fmu(gains[i], 0.0, 0.0, NULL, NULL, 0) == 0);
        CHECK(step_gain(gains[i], 2.0 + i) == 2.0 + i);
    }
    ssx_fmu_counters counters;
    ssx_fmu_get_counters(gains[1], &counters);
    CHECK(counters.do_step == 1 && counters.set_values == 1 && counters.get_values == 1);

    /* the pool released while its bindings live; a binding freed in between is reused */
    ssx_fmu_free(gains[1]);
    ssx_fmu *reloaded = load_fmu_in("gain", pool);
    CHECK(reloaded == gains[1]);
    ssx_fmu_get_counters(reloaded, &counters);
    CHECK(counters.do_step == 0);
    ssx_binding_pool_release(pool);
    CHECK(start_fmu(reloaded, 0.0, 0.0, NULL, NULL, 0) == 0);
    CHECK(step_gain(reloaded, 7.0) == 7.0);
    ssx_fmu_free(gains[2]);
    ssx_fmu_free(reloaded);
    ssx_fmu_free(gains[0]);
}

int main(void)
{
    slots_side_by_side();
    chunks_grow_to_large_pages();
    bindings_in_a_pool();
    return 0;
}
