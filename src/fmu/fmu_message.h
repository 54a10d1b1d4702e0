/* Formatting what an FMU logs. Shared by the engine and the FMU host process. */
#ifndef SSX_FMU_MESSAGE_H
#define SSX_FMU_MESSAGE_H

#include <stdarg.h>
#include <stddef.h>

/* At most this many arguments are read for one message. */
enum { SSX_FMU_MESSAGE_MAX_ARGUMENTS = 16 };

/* FMI 1.0 and 2.0 hand the logger a printf format and its arguments, but the master cannot
 * know how many arguments an FMU really passed, and some FMUs pass none with a format that
 * asks for some (their text, formatted already, is the format). So the format is interpreted
 * here, bounded by `size`, never by vsnprintf:
 * - a number or character conversion (d i o u x X e E f F g G a A c p, with any flags, width,
 *   precision and length) is formatted from its argument, read by value: a missing one shows
 *   as a meaningless number, it is never read through;
 * - a string conversion (%s) is never read through, for its argument may be missing and a
 *   garbage pointer is a crash: its text stays as written (its argument is skipped);
 * - "%%" is a percent sign; any other conversion ('*' widths, "%n", which writes, an unknown
 *   letter) stays as written and ends the reading: later conversions stay as written too, as
 *   do those after the first SSX_FMU_MESSAGE_MAX_ARGUMENTS arguments. */
void ssx_format_fmu_message(char *out, size_t size, const char *format, va_list args);

#endif
