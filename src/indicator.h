/* Event indicators: evaluation and the sign logic of crossing detection.
 *
 * The rule (as CVODE's root finding treats an exact zero): an indicator crosses when it leaves
 * its side, and reaching zero exactly is already that crossing. An indicator that crossed onto
 * zero rests there: while it stays at zero nothing crosses, and leaving zero (to either side)
 * is no new crossing; the side it leaves to becomes its side. So a value that touches or rests
 * on zero makes one crossing, and a value that never reaches zero makes none. */
#ifndef SSX_INDICATOR_H
#define SSX_INDICATOR_H

#include "system.h"

/* Evaluates every indicator at the current state (time t) into its value. */
int indicators_evaluate(ssx_system *sys, double t);
/* -1 / +1 when z lies on the far side of the indicator's sign or on zero (and the indicator
 * does not rest on zero already), else 0. */
int indicator_crossing(const ssx_indicator *ind, double z);
/* A crossing in the indicator's direction. */
int indicator_fires(const ssx_indicator *ind, double z);
/* After accepting a state with value z: flips the sign on a crossing (any direction), starts
 * or ends a rest on zero. With no side yet (sign 0), takes the side of z. */
void indicator_follow(ssx_indicator *ind, double z);

#endif
