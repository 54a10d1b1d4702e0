/* The GUID of an FMU, derived from its variable table so the binary and the XML always agree. */
#ifndef SYSSIMX_FMU_GUID_H
#define SYSSIMX_FMU_GUID_H

#define FMU_GUID_LENGTH 39 /* "{8-4-4-4-12}" plus the terminating zero */

void fmu_guid(char guid[FMU_GUID_LENGTH]);

#endif
