/* Event indicators: evaluation and the sign logic of crossing detection.
 *
 * The rule (as CVODE's root finding treats an exact zero): an indicator crosses when it leaves
 * its side, and reaching zero exactly is already that crossing. An indicator that crossed onto
 * zero rests there: while it stays at zero nothing crosses, and leaving zero (to either side)
 * is no new crossing; the side it leaves to becomes its side. So a value that touches or rests
 * on zero makes one crossing, and a value that never reaches zero makes none. */
#ifndef SSX_INDICATOR_H
#define SSX_INDICATOR_H

#include "syssimx_engine.h"

/* What an indicator is, as built: which value it watches and which crossings fire. */
typedef struct ssx_indicator {
    int component;
    int output; /* -1 for a callback indicator */
    int (*evaluate)(void *user, double t, double *value);
    void *user;
    int direction;
    int has_slope;          /* its time derivative can be read from the component's FMU: */
    unsigned int slope_vr;  /* the Real variable holding it (ssx_set_indicator_slope) */
} ssx_indicator;

/* Where an indicator stands in a run: its value, its side, its events so far. */
typedef struct indicator_state {
    double value;
    int sign;    /* side the indicator is on: -1 or +1; 0 while unknown (started at zero) */
    int on_zero; /* reached exactly zero in its last crossing and stays there: no new crossing
                    until it leaves zero, whichever side it leaves to */
    int fired_before;
    double last_event_time;
    double last_interval; /* between its last two events (infinite after the first) */
    long fire_count;
} indicator_state;

/* Marks the outputs the indicators read as feeding something (finite_outputs.h), after
 * finite_outputs_watch. */
void indicators_watch_outputs(ssx_system *sys);
/* Evaluates every indicator at the current state (time t) into its state's value. */
int indicators_evaluate(ssx_system *sys, double t);
/* Indicator i's time derivative at the current state (time t) into *slope, NAN when it has
 * none; 0, or -1 with the error set when the FMU refuses the read. */
int indicator_slope(ssx_system *sys, int i, double t, double *slope);
/* At ssx_initialize, once the values at t0 are evaluated: no events yet, each indicator on
 * the side of its value (none when it is zero). */
void indicators_start(ssx_system *sys);
/* -1 / +1 when z lies on the far side of the indicator's sign or on zero (and the indicator
 * does not rest on zero already), else 0. */
int indicator_crossing(const indicator_state *s, double z);
/* A crossing in the indicator's direction. */
int indicator_fires(const ssx_indicator *ind, const indicator_state *s, double z);
/* After accepting a state with value z: flips the sign on a crossing (any direction), starts
 * or ends a rest on zero. With no side yet (sign 0), takes the side of z. */
void indicator_follow(indicator_state *s, double z);

#endif
