/* The back-end of models without continuous states: a step only advances time. */
#include "fmu_solver.h"

const model_variable fmu_solver_variables[] = {{0}};
const size_t fmu_solver_variable_count = 0;
const char fmu_solver_name[] = "none";

int fmu_solver_create(fmu_instance *inst)
{
    return inst->model->n_states == 0 ? 0 : -1;
}

void fmu_solver_free(fmu_instance *inst)
{
    (void)inst;
}

void fmu_solver_invalidate(fmu_instance *inst)
{
    (void)inst;
}

fmu_status fmu_solver_step(fmu_instance *inst, double t_end)
{
    inst->time = t_end;
    return FMU_OK;
}
