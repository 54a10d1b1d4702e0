/* The components' Python record hooks, an observer of every sample: each component with a
 * record hook is called at the sample's time, in component order. */
#ifndef SSX_RECORD_HOOKS_H
#define SSX_RECORD_HOOKS_H

#include "observer.h"

/* NULL when out of memory; the recording that takes it frees it. */
ssx_observer *record_hooks_observer_new(void);

#endif
