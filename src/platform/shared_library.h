/* A shared library loaded into this process: the one place that knows how the operating system
 * loads one and finds its symbols (dlopen on POSIX systems). */
#ifndef SSX_SHARED_LIBRARY_H
#define SSX_SHARED_LIBRARY_H

/* The library at path, its symbols bound now and kept to itself; NULL with *reason set (a
 * text the system owns) when it cannot be loaded. */
void *shared_library_open(const char *path, const char **reason);
/* The address of the exported symbol name, NULL when the library lacks it. */
void *shared_library_symbol(void *library, const char *name);
void shared_library_close(void *library);

#endif
