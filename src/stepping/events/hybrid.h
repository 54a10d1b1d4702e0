/* The hybrid macro step (active whenever the system has event indicators). */
#ifndef SSX_HYBRID_H
#define SSX_HYBRID_H

#include "system.h"

/* Allocates the indicators' states and the algorithm's own workspace (localization) for the
 * system as built. */
int hybrid_prepare(ssx_system *sys, void **workspace);
void hybrid_release(ssx_system *sys, void *workspace);
/* Advances the system from `from` in the communication step [t, t_next] to t_next, or to the
 * first event located and handled in between (*event set). */
int hybrid_step(ssx_system *sys, double t, double from, double t_next, int *event);

/* What the hybrid algorithm carries between steps (algorithm.h): carried[0], whether the
 * indicators that started on zero still wait for their side. */
void hybrid_carry_out(const ssx_system *sys, double *carried);
void hybrid_carry_in(ssx_system *sys, const double *carried);

/* The snapshot slot of a macro piece's start: localization restores it. */
enum { MACRO_SLOT = 0 };

/* A macro piece for an algorithm that chooses its own steps (adaptive.h): begin at a0 (an
 * indicator starting on zero is resolved there), then take the MACRO_SLOT snapshot and the
 * coupled step to t_end, then end the piece: the earliest crossing in it is located to
 * tol_time and handled. *reached is where the system is then: t_end, or the event's instant
 * (*event set), or a listened output clock's tick inside the piece (the next piece starts
 * there), or, rarely, a point before t_end where the trajectory the localization followed
 * has not crossed yet (the next piece starts there); the grid point is not recorded. */
typedef struct {
    double a0;
    long do_steps_before; /* statistics at the piece's start, for the event's cost */
    long restores_before;
} hybrid_piece;
int hybrid_begin_piece(ssx_system *sys, double a0, double t_end, hybrid_piece *piece);
int hybrid_end_piece(ssx_system *sys, const hybrid_piece *piece, double t_end, double grid_step,
                     double *reached, int *event);

#endif
