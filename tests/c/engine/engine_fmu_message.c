/* The formatter of what FMUs log (src/fmu/fmu_message.c): numbers are formatted, string
 * arguments are never read through, and what it cannot read stays as written. Compiled in: the
 * formatter is internal to the library. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmu_message.h"

static int failures;

static void expect(const char *expected, size_t size, const char *format, ...)
{
    char out[256];
    memset(out, 'x', sizeof out);
    va_list args;
    va_start(args, format);
    ssx_format_fmu_message(out, size, format, args);
    va_end(args);
    if (strcmp(out, expected) != 0) {
        fprintf(stderr, "FAIL: format \"%s\" gave \"%s\", expected \"%s\"\n", format, out,
                expected);
        ++failures;
    }
}

int main(void)
{
    enum { ROOM = 256 };
    expect("plain text", ROOM, "plain text");
    expect("100% sure", ROOM, "100%% sure");
    expect("3 apples, 2.50 kg, x, 7, 42, ff", ROOM, "%d apples, %.2f kg, %c, %ld, %zu, %x", 3,
           2.5, 'x', 7L, (size_t)42, 255u);
    expect("[    -4|+1.5e+00]", ROOM, "[%6d|%+.1e]", -4, 1.5);
    expect("9007199254740993", ROOM, "%lld", 9007199254740993LL);
    /* a string argument is skipped, not read; the numbers after it still line up */
    expect("name %s, 5 items", ROOM, "name %s, %d items", "solver", 5);
    expect("%s%s%n", ROOM, "%s%s%n");
    /* '*' and unknown conversions stay as written, and so does everything after them */
    expect("%*d and %d", ROOM, "%*d and %d", 4, 1, 2);
    expect("%m then %d", ROOM, "%m then %d", 1);
    expect("ends with %", ROOM, "ends with %");
    /* the output is cut to its size, always terminated */
    expect("abcd", 5, "abcdefgh");
    expect("12", 3, "%d", 12345);
    /* past the arguments read at most, conversions stay as written */
    expect("1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 %d", ROOM,
           "%d %d %d %d %d %d %d %d %d %d %d %d %d %d %d %d %d", 1, 2, 3, 4, 5, 6, 7, 8, 9, 10,
           11, 12, 13, 14, 15, 16, 17);
    if (failures == 0) {
        printf("fmu_message: all formats as expected\n");
    }
    return failures != 0;
}
