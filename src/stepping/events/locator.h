/* Event localization methods: where to try next inside the bracket, and what a trial changes
 * in their per-indicator workspace. A new method is one row of the table in locator.c. */
#ifndef SSX_LOCATOR_H
#define SSX_LOCATOR_H

#include "syssimx_engine.h"

enum { SIDE_NONE = 0, SIDE_LEFT = 1, SIDE_RIGHT = 2 };
enum { LOCATOR_UNBOUNDED = -1 };

/* The bracket during localization, as the methods see it. */
typedef struct {
    double a, b;
    double replaced;  /* where the end that the last trial replaced was; NAN before any trial */
    int moved;        /* which end the last trial replaced (SIDE_*) */
    int moved_before; /* which end the trial before replaced */
    double tol_time;  /* the tolerances: how close to the bracket a trial may lie, and where a
                       * method aims past a zero it knows well */
    double tol_value;
} bracket_state;

/* One indicator at the bracket ends: the localization workspace, one per indicator. */
typedef struct {
    double z_left, z_right; /* values at the bracket ends */
    double w_left, w_right; /* Illinois-weighted values at the bracket ends */
    double z_replaced;      /* value at the end the last trial replaced */
    double d_left, d_right; /* time derivatives at the bracket ends, NAN where unknown */
    int crossing;           /* crosses (in its direction) at the current right end */
} indicator_bracket;

typedef struct {
    /* Where to try next; NAN (or a point outside the bracket) leaves it to bisection. */
    double (*estimate)(const indicator_bracket *ends, int n, const bracket_state *st);
    /* After a trial has moved one end (st->moved). */
    void (*after_trial)(indicator_bracket *ends, int n, const bracket_state *st);
    int slack; /* at most bisection's iterations plus slack, or LOCATOR_UNBOUNDED */
} locator_method;

/* Each method's name by its ssx_locator, as a plan writes it (the enum's name in lower case,
 * as Python reads it from the header), then NULL. */
extern const char *const locator_names[];
/* locator names a localization method (an ssx_locator). */
int locator_known(int locator);
const locator_method *locator_method_of(ssx_locator locator);
/* Most trials the method may take to shrink a bracket of width w to tol, or LOCATOR_UNBOUNDED. */
int locator_budget(const locator_method *method, double w, double tol);
/* The next trial time in the bracket. A budgeted method's estimate is kept where, whichever
 * end the trial replaces, the bracket left over still comes down to final_width by halving
 * within the remaining budget: budget - done - 1 halvings after this trial. */
double locator_next_trial(const locator_method *method, const indicator_bracket *ends, int n,
                          const bracket_state *st, double final_width, int budget, int done);

#endif
