/* Formatting what an FMU logs, refusing the conversion that writes to memory. */
#include "fmu_message.h"

#include <stdio.h>
#include <string.h>

/* Whether the format has a "%n" conversion (with any flags, width, precision or length). */
static int writes_through_argument(const char *format)
{
    for (const char *p = strchr(format, '%'); p != NULL; p = strchr(p, '%')) {
        ++p;
        if (*p == '%') {
            ++p;
            continue;
        }
        p += strspn(p, "-+ #0'123456789.*$hlLqjzt");
        if (*p == 'n') {
            return 1;
        }
    }
    return 0;
}

void ssx_format_fmu_message(char *out, size_t size, const char *format, va_list args)
{
    if (size == 0) {
        return;
    }
    if (writes_through_argument(format)) {
        snprintf(out, size, "%s", format);
        return;
    }
    vsnprintf(out, size, format, args);
}
