/* The localization trials of the event records. */
#include "localization_log.h"

#include <math.h>
#include <stdlib.h>

#include "array.h"

enum { END_ROWS = 2, ROW_HEAD = 3 };

void localization_log_free(ssx_localization_log *log)
{
    free(log->rows);
    free(log->trials);
    *log = (ssx_localization_log){0};
}

void localization_log_clear(ssx_localization_log *log)
{
    log->n_rows = 0;
    log->n_trials = 0;
}

void localization_log_begin(ssx_localization_log *log, int n_indicators)
{
    log->n_rows = 0;
    log->stride = ROW_HEAD + (size_t)n_indicators;
}

double *localization_log_row(ssx_localization_log *log, double t, double a, double b)
{
    if (array_reserve((void **)&log->rows, &log->rows_capacity, (log->n_rows + 1) * log->stride,
                      sizeof *log->rows, 32 * log->stride) != 0) {
        return NULL;
    }
    double *row = log->rows + log->n_rows++ * log->stride;
    row[0] = t;
    row[1] = a;
    row[2] = b;
    return row + ROW_HEAD;
}

int localization_log_publish(ssx_localization_log *log, ssx_event_record *record)
{
    if (log->n_rows < END_ROWS) {
        localization_log_none(log, record);
        return 0;
    }
    size_t column = ROW_HEAD + (size_t)record->indicator;
    size_t n = log->n_rows - END_ROWS;
    if (array_reserve((void **)&log->trials, &log->trials_capacity, log->n_trials + n,
                      sizeof *log->trials, 64) != 0) {
        return -1;
    }
    const double *left = log->rows;
    const double *right = log->rows + log->stride;
    record->t_left = left[0];
    record->value_left = left[column];
    record->t_right = right[0];
    record->value_right = right[column];
    record->first_trial = log->n_trials;
    record->n_trials = (int)n;
    for (size_t k = 0; k < n; ++k) {
        const double *row = log->rows + (END_ROWS + k) * log->stride;
        log->trials[log->n_trials++] =
            (ssx_localization_trial){.t = row[0], .a = row[1], .b = row[2], .value = row[column]};
    }
    return 0;
}

void localization_log_none(const ssx_localization_log *log, ssx_event_record *record)
{
    record->t_left = record->t_right = NAN;
    record->value_left = record->value_right = NAN;
    record->first_trial = log->n_trials;
    record->n_trials = 0;
}
