/* The hybrid macro step (active whenever the system has event indicators). */
#ifndef SSX_HYBRID_H
#define SSX_HYBRID_H

#include "system.h"

/* Advances the system from t to t_next, locating and handling every event in between. */
int hybrid_step(ssx_system *sys, double t, double t_next);
/* locator names a localization method (an ssx_locator). */
int hybrid_locator_known(int locator);

#endif
