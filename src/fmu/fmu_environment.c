/* Where an FMU's log messages go: formatted safely into its environment's last message. */
#include "fmu_environment.h"

#include "fmu_message.h"

void ssx_fmu_environment_log(ssx_fmu_environment *environment, const char *format,
                             va_list args)
{
    ssx_format_fmu_message(environment->last_message, sizeof environment->last_message, format,
                           args);
}
