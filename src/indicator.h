/* Event indicators: evaluation and the sign logic of crossing detection. */
#ifndef SSX_INDICATOR_H
#define SSX_INDICATOR_H

#include "system.h"

/* Evaluates every indicator at the current state (time t) into its value. */
int indicators_evaluate(ssx_system *sys, double t);
/* -1 / +1 when z lies on the far side of the indicator's sign (zero counts as far), else 0. */
int indicator_crossing(const ssx_indicator *ind, double z);
/* A crossing in the indicator's direction. */
int indicator_fires(const ssx_indicator *ind, double z);
/* After accepting a state with value z: flips the sign on a crossing (any direction). */
void indicator_follow(ssx_indicator *ind, double z);

#endif
