/* Memory a pool or arena holds but has not handed out, marked for AddressSanitizer: a block
 * read after it was given back, or past its end, is reported as with malloc, although the
 * pool, not malloc, holds it. Without the sanitizer these do nothing. */
#ifndef SSX_POISON_H
#define SSX_POISON_H

#if defined(__SANITIZE_ADDRESS__)
#define SSX_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SSX_ASAN 1
#endif
#endif

#ifdef SSX_ASAN
#include <sanitizer/asan_interface.h>
#define POISON(address, size) ASAN_POISON_MEMORY_REGION((address), (size))
#define UNPOISON(address, size) ASAN_UNPOISON_MEMORY_REGION((address), (size))
/* bytes left poisoned after each block of an arena, to catch a write past its end */
enum { POISON_REDZONE = 16 };
#else
#define POISON(address, size) ((void)(address), (void)(size))
#define UNPOISON(address, size) ((void)(address), (void)(size))
enum { POISON_REDZONE = 0 };
#endif

#endif
