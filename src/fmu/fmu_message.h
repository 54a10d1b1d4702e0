/* Formatting what an FMU logs. Shared by the engine and the FMU host process. */
#ifndef SSX_FMU_MESSAGE_H
#define SSX_FMU_MESSAGE_H

#include <stdarg.h>
#include <stddef.h>

/* FMI 2.0 hands the logger a printf format and its arguments, but the master cannot know how
 * many arguments an FMU really passed: a format asking for more makes vsnprintf read garbage,
 * and a "%n" conversion makes it write through a garbage pointer. A format with a "%n"
 * conversion is therefore never interpreted: `out` receives its raw text. */
void ssx_format_fmu_message(char *out, size_t size, const char *format, va_list args);

#endif
