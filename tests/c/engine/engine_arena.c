/* The arena a system's component blocks are made in: blocks zeroed, aligned and in the order
 * made, chunks that double up to one 2 MiB large page on its boundary, a block larger than a
 * chunk, freeing all at once and using the arena again (under AddressSanitizer a block read
 * past its end, or after the arena was freed, is reported); an arena told how much it will
 * hold starting with a chunk that size. Then a system of many components, whose blocks and
 * prepared step data are arenas', stepped, initialized and stepped again, and freed. */
#include <stdint.h>
#include <string.h>

#include "arena.h"
#include "test_support.h"

enum { LINE = 64, BLOCK = 520 };

static int zeroed(const unsigned char *block, size_t size)
{
    for (size_t i = 0; i < size; ++i) {
        if (block[i] != 0) {
            return 0;
        }
    }
    return 1;
}

static void blocks_in_order(void)
{
    arena a = ARENA_EMPTY;
    unsigned char *first = arena_allocate(&a, 24, 8);
    unsigned char *second = arena_allocate(&a, BLOCK, LINE);
    unsigned char *third = arena_allocate(&a, 3, 1);
    CHECK(first != NULL && second != NULL && third != NULL);
    CHECK((uintptr_t)first % LINE == 0); /* a chunk's first block starts on a line */
    CHECK((uintptr_t)second % LINE == 0 && second > first && second - first <= 2 * LINE);
    CHECK(third >= second + BLOCK && third - second <= BLOCK + LINE);
    CHECK(zeroed(first, 24) && zeroed(second, BLOCK) && zeroed(third, 3));
    memset(second, 0xA5, BLOCK);
    CHECK(third[0] == 0 && first[23] == 0);
    CHECK(arena_allocate(&a, 8, 3) == NULL && arena_allocate(&a, 8, 128) == NULL);
    arena_free(&a);
    CHECK(a.chunks == NULL && a.next == NULL && a.left == 0);
    /* empty again: usable as a new one */
    unsigned char *again = arena_allocate(&a, BLOCK, LINE);
    CHECK(again != NULL && zeroed(again, BLOCK));
    arena_free(&a);
}

/* 16 KiB, 32 KiB, ... 1 MiB chunks, then 2 MiB ones on a 2 MiB boundary. */
static void chunks_grow_to_large_pages(void)
{
    arena a = ARENA_EMPTY;
    size_t small = 0; /* bytes of the chunks below 2 MiB */
    for (size_t bytes = 16 * 1024; bytes < ((size_t)2 << 20); bytes *= 2) {
        small += bytes;
    }
    uintptr_t large_page = (uintptr_t)2 << 20;
    int on_boundary = 0;
    for (size_t made = 0; made < small / BLOCK + 3 * (large_page / BLOCK); ++made) {
        unsigned char *block = arena_allocate(&a, BLOCK, LINE);
        CHECK(block != NULL);
        on_boundary += ((uintptr_t)block - LINE) % large_page == 0;
    }
    CHECK(on_boundary >= 2); /* the second and third 2 MiB chunks at least */
    /* a block larger than the next chunk gets a chunk of its own */
    unsigned char *huge = arena_allocate(&a, (size_t)5 << 20, LINE);
    CHECK(huge != NULL && zeroed(huge, (size_t)5 << 20));
    arena_free(&a);
}

/* An arena told it will hold 3 MiB starts on a large page; one told 100 KiB holds that much
 * in its first chunk; a told size does not change a chunk already made. */
static void expected_size(void)
{
    uintptr_t large_page = (uintptr_t)2 << 20;
    arena a = ARENA_EMPTY;
    arena_expect(&a, (size_t)3 << 20);
    unsigned char *first = arena_allocate(&a, BLOCK, LINE);
    CHECK(first != NULL && ((uintptr_t)first - LINE) % large_page == 0);
    arena_free(&a);

    arena_expect(&a, 100 * 1024);
    first = arena_allocate(&a, BLOCK, LINE);
    const arena_chunk *first_chunk = a.chunks;
    /* blocks with their alignment (and redzones) filling about 100 KiB */
    for (size_t made = 1; made < 100 * 1024 / (BLOCK + 2 * LINE); ++made) {
        CHECK(arena_allocate(&a, BLOCK, LINE) != NULL);
    }
    CHECK(first != NULL && a.chunks == first_chunk); /* all in the first chunk */
    arena_expect(&a, (size_t)3 << 20);
    CHECK(a.next_chunk_bytes < large_page); /* made already: the next chunk doubles as before */
    arena_free(&a);
}

/* Gain: y = k * u with k = 1; a chain of 300 stepped through the engine and freed. */
enum { GAIN_Y = 0, GAIN_U = 1, CHAIN = 300 };

static void components_in_the_arena(void)
{
    ssx_system *sys = ssx_system_new("chain");
    static ssx_fmu *gains[CHAIN];
    for (int i = 0; i < CHAIN; ++i) {
        char name[16];
        snprintf(name, sizeof name, "g%d", i);
        gains[i] = load_fmu("gain");
        CHECK(start_fmu(gains[i], 0.0, 0.0, NULL, NULL, 0) == 0);
        int c = ssx_add_fmu_component(sys, name, gains[i], 1);
        CHECK(c == i);
        CHECK(ssx_add_output(sys, c, SSX_REAL, GAIN_Y) == 0);
        CHECK(ssx_add_input(sys, c, SSX_REAL, GAIN_U, i == 0 ? 2.0 : 0.0) == 0);
        if (i > 0) {
            CHECK_OK(sys, ssx_connect(sys, i - 1, 0, i, 0, 1.0, 0.0));
        }
    }
    /* twice: the second initialize gives the prepared step data back and makes it again
     * (under AddressSanitizer a pointer kept into the old blocks is reported) */
    for (int round = 0; round < 2; ++round) {
        double t0 = 0.01 * round; /* the FMUs go on from where the first run left them */
        CHECK_OK(sys, ssx_initialize(sys, t0));
        CHECK_OK(sys, ssx_run(sys, t0, t0 + 0.01, 1e-3));
        const double *last = ssx_history_values(sys, CHAIN - 1);
        CHECK(last[ssx_history_length(sys) - 1] == 2.0);
    }
    ssx_system_free(sys);
    for (int i = 0; i < CHAIN; ++i) {
        ssx_fmu_free(gains[i]);
    }
}

int main(void)
{
    blocks_in_order();
    chunks_grow_to_large_pages();
    expected_size();
    components_in_the_arena();
    return 0;
}
