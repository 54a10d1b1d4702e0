/* The hybrid macro step (active whenever the system has event indicators). */
#ifndef SSX_HYBRID_H
#define SSX_HYBRID_H

#include "system.h"

/* Allocates the indicators' states and localization workspace for the system as built. */
int hybrid_prepare(ssx_system *sys);
/* Advances the system from t to t_next, locating and handling every event in between. */
int hybrid_step(ssx_system *sys, double t, double t_next);

#endif
