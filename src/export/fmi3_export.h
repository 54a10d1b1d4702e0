/* The FMI 3.0 instance of an exported system, shared by its entry points (fmi3_export.c) and
 * the functions it declines (fmi3_declined.c). */
#ifndef SSX_FMI3_EXPORT_H
#define SSX_FMI3_EXPORT_H

#include "exported_system.h"

#include "fmi3Functions.h"

typedef enum {
    MODE3_INSTANTIATED,
    MODE3_INITIALIZATION,
    MODE3_EVENT,
    MODE3_STEP,
    MODE3_TERMINATED,
    MODE3_ERROR
} fmi3_mode;

typedef struct {
    exported_system *system;
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback log_message;
    int logging_on;
    int event_mode_used;
    int early_return_allowed;
    fmi3_mode mode;
    int terminated_by_member;
} fmi3_instance;

/* Logs `what` as an error through the importer's callback and returns fmi3Error. */
fmi3Status fmi3_refuse(fmi3Instance instance, const char *what);

#endif
