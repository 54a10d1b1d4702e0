/* The trials of event localization, kept for the event records: during localization a scratch
 * table with every indicator's value per trial (which indicators fire is known only after
 * it), then per event record the trials with that record's indicator. Both buffers are reused
 * across events and grow geometrically; nothing is written when no event happens. */
#ifndef SSX_LOCALIZATION_LOG_H
#define SSX_LOCALIZATION_LOG_H

#include <stddef.h>

#include "syssimx_engine.h"

typedef struct {
    double *rows;         /* scratch: n_rows x stride: t, a, b, then every indicator's value */
    size_t n_rows;
    size_t rows_capacity; /* doubles */
    size_t stride;
    ssx_localization_trial *trials; /* published, indexed by ssx_event_record.first_trial */
    size_t n_trials;
    size_t trials_capacity;
} ssx_localization_log;

void localization_log_free(ssx_localization_log *log);
/* Drops the published trials (a new run). */
void localization_log_clear(ssx_localization_log *log);
/* Starts the scratch of one localization of n_indicators indicators. Its first two rows are
 * the ends of the initial bracket, then one row per trial. */
void localization_log_begin(ssx_localization_log *log, int n_indicators);
/* Appends a scratch row (t, bracket [a, b] after it) and returns where its n_indicators values
 * go; NULL when out of memory. */
double *localization_log_row(ssx_localization_log *log, double t, double a, double b);
/* Fills the localization fields of record (for its indicator) and publishes its trials. */
int localization_log_publish(ssx_localization_log *log, ssx_event_record *record);
/* The localization fields of a record without localization. */
void localization_log_none(const ssx_localization_log *log, ssx_event_record *record);

#endif
