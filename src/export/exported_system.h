/* An exported system: the engine's system built from the FMU's resources (the plan, the export
 * map, the member FMUs), behind what both FMI versions' entry points need. No FMI types here:
 * fmi2_export.c and fmi3_export.c translate. */
#ifndef SSX_EXPORTED_SYSTEM_H
#define SSX_EXPORTED_SYSTEM_H

#include <stddef.h>

/* How a message reaches the importer: error nonzero for a failure. */
typedef void (*exported_log)(void *user, int error, const char *message);

typedef struct exported_system exported_system;
typedef struct exported_state exported_state;

/* Reads resources/export.map and resources/system.plan (resources: a folder path) and checks
 * the token; the members are built from resources/members when the system starts. NULL with
 * the reason logged on failure. */
exported_system *exported_system_new(const char *resources, const char *token, exported_log log,
                                     void *user);
void exported_system_free(exported_system *es);
/* Forget the run: the values set and the built system (fmi2Reset, fmi3Reset). */
void exported_system_reset(exported_system *es);

/* Build the members from the plan with the parameters set so far, initialize them at t0 with
 * the inputs set so far, and initialize the system: the start of initialization mode. A
 * parameter set in initialization mode builds it again; at its end (exported_system_steps)
 * parameters are fixed. */
int exported_system_start(exported_system *es, double t0);
void exported_system_steps(exported_system *es);
/* Before exported_system_start: steps return early at members' own events too, not only at the
 * indicators' (ssx_set_stop_at_own_events; the FMI 3.0 export when early return is allowed). */
void exported_system_stop_at_own_events(exported_system *es, int stop);

/* Values by exported value reference: 0, or -1 (logged, naming the variable) for an unknown
 * reference, a variable of another type, an output set, or a parameter set after
 * initialization mode. The integer ones are Integer variables, or with `boolean` Boolean ones
 * (0 or 1). */
int exported_system_set_real(exported_system *es, const unsigned int *vr, size_t n,
                             const double *values);
int exported_system_get_real(exported_system *es, const unsigned int *vr, size_t n, double *values);
int exported_system_set_integer(exported_system *es, const unsigned int *vr, size_t n,
                                const int *values, int boolean);
int exported_system_get_integer(exported_system *es, const unsigned int *vr, size_t n, int *values,
                                int boolean);

/* Advance from t (the system's time) by h, locating and handling the events inside. With
 * may_return_early, returns right after the first event instant (*reached: its time,
 * *returned_early set): an indicator's, or a member's own where the system stops at those.
 * 0: done; 1: a member asked to end the simulation at *reached; -1: failed (logged). */
int exported_system_step(exported_system *es, double t, double h, int may_return_early,
                         double *reached, int *returned_early);
double exported_system_time(const exported_system *es);

/* The whole system's state (every member's and the engine's), with the events counted. */
exported_state *exported_state_save(exported_system *es);
int exported_state_restore(exported_system *es, const exported_state *state);
void exported_state_free(exported_state *state);
/* malloc'd bytes; NULL (logged) on failure */
unsigned char *exported_state_serialize(exported_system *es, const exported_state *state,
                                        size_t *size);
exported_state *exported_state_deserialize(exported_system *es, const unsigned char *bytes,
                                           size_t size);

#endif
