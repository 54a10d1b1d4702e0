/* Shared libraries on POSIX systems (see shared_library.h). */
#include "shared_library.h"

#include <dlfcn.h>
#include <stddef.h>

void *shared_library_open(const char *path, const char **reason)
{
    void *library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (library == NULL) {
        const char *text = dlerror();
        *reason = text != NULL ? text : "unknown dlopen failure";
    }
    return library;
}

void *shared_library_symbol(void *library, const char *name)
{
    return dlsym(library, name);
}

void shared_library_close(void *library)
{
    dlclose(library);
}
