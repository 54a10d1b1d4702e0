/* What an FMU's callbacks reach through the environment pointer the back-end hands the FMU:
 * where its log messages go, and, for an FMU run by a host process, that host. The binding
 * owns one per FMU; the back-ends and the forwarding functions of isolation use it without
 * knowing the binding. */
#ifndef SSX_FMU_ENVIRONMENT_H
#define SSX_FMU_ENVIRONMENT_H

#include <stdarg.h>

typedef struct ssx_remote ssx_remote;

typedef struct {
    ssx_remote *remote; /* an isolated FMU's host process; NULL when the binary runs here */
    char last_message[1024];
} ssx_fmu_environment;

/* Keeps what the FMU logged, a printf format with its arguments, as its last message. */
void ssx_fmu_environment_log(ssx_fmu_environment *environment, const char *format,
                             va_list args);

#endif
