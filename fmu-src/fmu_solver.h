/* The back-end interface. Exactly one back-end (euler, cvode or none) is linked into an FMU. */
#ifndef SYSSIMX_FMU_SOLVER_H
#define SYSSIMX_FMU_SOLVER_H

#include "fmu_instance.h"

/* Parameters the back-end adds to the model's variable table (after the model's variables). */
extern const model_variable fmu_solver_variables[];
extern const size_t fmu_solver_variable_count;
extern const char fmu_solver_name[];

int fmu_solver_create(fmu_instance *inst);  /* 0 on success */
void fmu_solver_free(fmu_instance *inst);
/* The state or an input was changed from outside: restart the integration from inst->x. */
void fmu_solver_invalidate(fmu_instance *inst);
/* Advance inst->time and inst->x to t_end (> inst->time). */
fmu_status fmu_solver_step(fmu_instance *inst, double t_end);

#endif
