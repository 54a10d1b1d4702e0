/* Observers of a run (libcosim's idea): the time loop reports what it completed and never
 * records anything itself; each observer decides what to keep. The history is one observer,
 * a decimating front of it another; streaming to disk or collecting an ensemble would each be
 * one more, without a change to the algorithms.
 *
 * Every member but step_complete may be NULL (step_complete is called for every sample, without
 * a check). Those returning int return 0, or -1 with the system's error set; a failing observer
 * stops the run. */
#ifndef SSX_OBSERVER_H
#define SSX_OBSERVER_H

#include <stddef.h>

#include "syssimx_engine.h"

/* A state the system completed; the components' outputs are its values. */
typedef struct {
    double t;
    int micro;   /* superdense index at t; -1 for a localization trial (record_internal_steps) */
    int on_grid; /* a communication point t0 + k*dt, micro 0, nothing happening there */
    int run_end; /* on_grid and the last point of the current ssx_run (or the sample at t0) */
} ssx_sample;

typedef struct ssx_observer ssx_observer;

typedef struct {
    /* ssx_initialize, before the sample at t0: the components and their outputs are final. */
    int (*start)(ssx_observer *self, ssx_system *sys);
    /* ssx_run is about to advance n_steps communication steps. */
    int (*run_start)(ssx_observer *self, ssx_system *sys, size_t n_steps);
    int (*step_complete)(ssx_observer *self, ssx_system *sys, const ssx_sample *sample);
    /* The system went back to a state saved at t (event localization, probing): what came
     * after t was a trial, not the trajectory. */
    int (*state_restored)(ssx_observer *self, ssx_system *sys, double t);
    /* An event was handled; its record is complete. */
    int (*event)(ssx_observer *self, ssx_system *sys, const ssx_event_record *record);
    /* ssx_run returns, whatever its status. */
    void (*run_end)(ssx_observer *self, ssx_system *sys);
} ssx_observer_ops;

/* Embedded first in each observer's own struct, which its functions cast back to. */
struct ssx_observer {
    const ssx_observer_ops *ops;
};

#endif
