/* The system's text table, as the public API gives it (syssimx_engine.h). */
#include "system.h"

int ssx_text_number(ssx_system *sys, const char *text, double *number)
{
    if (sys == NULL || number == NULL) {
        return -1;
    }
    return text_table_number(&sys->texts, text, number);
}

int ssx_bytes_number(ssx_system *sys, const void *data, size_t size, double *number)
{
    if (sys == NULL || number == NULL) {
        return -1;
    }
    return text_table_bytes_number(&sys->texts, data, size, number);
}

const char *ssx_text(ssx_system *sys, double number)
{
    return sys != NULL ? text_table_text(&sys->texts, number) : NULL;
}

const unsigned char *ssx_bytes(ssx_system *sys, double number, size_t *size)
{
    if (sys == NULL || size == NULL) {
        return NULL;
    }
    return text_table_bytes(&sys->texts, number, size);
}

size_t ssx_text_count(ssx_system *sys)
{
    return sys != NULL ? text_table_count(&sys->texts) : 0;
}
