/* SUNDIALS CVODE: BDF with Newton iteration and a dense linear solver. Integrates exactly to
 * the communication point (stop time), locates the model's internal events by root finding
 * (and stops at the first one when the importer handles events), and restarts (CVodeReInit)
 * only after an event, a changed input or a set state. */
#include <math.h>
#include <stdlib.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "fmu_evaluation.h"
#include "fmu_log.h"
#include "fmu_solver.h"

enum { CVODE_RELATIVE_TOLERANCE };

const model_variable fmu_solver_variables[] = {
    REAL_PARAMETER(CVODE_RELATIVE_TOLERANCE, "cvode_relative_tolerance", NULL, 1e-6,
                   "CVODE relative tolerance, used when fmi2SetupExperiment "
                   "defines none"),
};
const size_t fmu_solver_variable_count = sizeof fmu_solver_variables / sizeof *fmu_solver_variables;
const char fmu_solver_name[] = "cvode";

/* States are of order one (angles, speeds, heights): the absolute tolerance is the relative
 * one scaled down so that it only matters near zero crossings of a state. */
#define ABSOLUTE_TOLERANCE_FACTOR 1e-2
#define MAX_STEPS_PER_CALL 1000000L
#define MAX_EVENTS_PER_STEP 10000

typedef struct {
    SUNContext context;
    void *cvode;
    N_Vector y;
    SUNMatrix jacobian;
    SUNLinearSolver linear_solver;
    int *roots;
    int must_restart;
} cvode_data;

static int right_hand_side(sunrealtype t, N_Vector y, N_Vector ydot, void *user)
{
    fmu_instance *inst = user;
    fmu_inputs_at(inst, t);
    inst->model->derivatives(inst->values, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    return 0;
}

static int indicators(sunrealtype t, N_Vector y, sunrealtype *z, void *user)
{
    fmu_instance *inst = user;
    fmu_inputs_at(inst, t);
    inst->model->event_indicators(inst->values, t, N_VGetArrayPointer(y), z);
    return 0;
}

static void report(int code, const char *module, const char *function, char *message, void *user)
{
    fmu_instance *inst = user;
    if (code < 0)
        fmu_error(inst, "%s %s: %s", module, function, message);
    else
        fmu_log(inst, FMU_OK, LOG_ALL, "%s %s: %s", module, function, message);
}

void fmu_solver_free(fmu_instance *inst)
{
    cvode_data *data = inst->solver;
    if (data == NULL)
        return;
    if (data->cvode != NULL)
        CVodeFree(&data->cvode);
    if (data->linear_solver != NULL)
        SUNLinSolFree(data->linear_solver);
    if (data->jacobian != NULL)
        SUNMatDestroy(data->jacobian);
    if (data->y != NULL)
        N_VDestroy(data->y);
    if (data->context != NULL)
        SUNContext_Free(&data->context);
    free(data->roots);
    free(data);
    inst->solver = NULL;
}

static int configure(fmu_instance *inst, cvode_data *data)
{
    const model_definition *model = inst->model;
    sunindextype n = (sunindextype)model->n_states;
    if (SUNContext_Create(NULL, &data->context) != 0)
        return -1;
    data->y = N_VNew_Serial(n, data->context);
    data->cvode = CVodeCreate(CV_BDF, data->context);
    data->jacobian = data->y ? SUNDenseMatrix(n, n, data->context) : NULL;
    data->linear_solver =
        data->jacobian ? SUNLinSol_Dense(data->y, data->jacobian, data->context) : NULL;
    if (data->y == NULL || data->cvode == NULL || data->linear_solver == NULL)
        return -1;
    /* placeholders: every integration starts with restart(), which sets y and the tolerances */
    N_VConst(0.0, data->y);
    if (CVodeSetErrHandlerFn(data->cvode, report, inst) != CV_SUCCESS ||
        CVodeInit(data->cvode, right_hand_side, inst->time, data->y) != CV_SUCCESS ||
        CVodeSStolerances(data->cvode, 1e-6, 1e-8) != CV_SUCCESS ||
        CVodeSetUserData(data->cvode, inst) != CV_SUCCESS ||
        CVodeSetLinearSolver(data->cvode, data->linear_solver, data->jacobian) != CV_SUCCESS ||
        CVodeSetMaxNumSteps(data->cvode, MAX_STEPS_PER_CALL) != CV_SUCCESS)
        return -1;
    size_t n_roots = model->n_event_indicators;
    if (n_roots > 0) {
        data->roots = calloc(n_roots, sizeof(int));
        if (data->roots == NULL ||
            CVodeRootInit(data->cvode, (int)n_roots, indicators) != CV_SUCCESS)
            return -1;
        for (size_t i = 0; i < n_roots; ++i)
            data->roots[i] = -1; /* indicators fire when falling */
        if (CVodeSetRootDirection(data->cvode, data->roots) != CV_SUCCESS)
            return -1;
    }
    data->must_restart = 1;
    return 0;
}

int fmu_solver_create(fmu_instance *inst)
{
    if (inst->model->n_states == 0)
        return -1;
    cvode_data *data = calloc(1, sizeof *data);
    if (data == NULL)
        return -1;
    inst->solver = data;
    if (configure(inst, data) != 0) {
        fmu_solver_free(inst);
        return -1;
    }
    return 0;
}

void fmu_solver_invalidate(fmu_instance *inst)
{
    cvode_data *data = inst->solver;
    data->must_restart = 1;
}

/* Restart the integration at inst->time from inst->x with the current tolerance. */
static fmu_status restart(fmu_instance *inst, cvode_data *data)
{
    double relative = inst->tolerance_defined
                          ? inst->tolerance
                          : fmu_solver_parameter(inst, CVODE_RELATIVE_TOLERANCE);
    if (!(relative > 0.0 && relative < 1.0))
        return fmu_error(inst, "the CVODE relative tolerance must be in (0, 1), it is %g",
                         relative);
    double *y = N_VGetArrayPointer(data->y);
    for (size_t i = 0; i < inst->model->n_states; ++i)
        y[i] = inst->x[i];
    if (CVodeReInit(data->cvode, inst->time, data->y) != CV_SUCCESS ||
        CVodeSStolerances(data->cvode, relative, relative * ABSOLUTE_TOLERANCE_FACTOR) !=
            CV_SUCCESS)
        return fmu_error(inst, "CVODE could not be restarted at t = %.17g", inst->time);
    data->must_restart = 0;
    return FMU_OK;
}

static void copy_state_out(fmu_instance *inst, const cvode_data *data)
{
    const double *y = N_VGetArrayPointer(data->y);
    for (size_t i = 0; i < inst->model->n_states; ++i)
        inst->x[i] = y[i];
}

fmu_status fmu_solver_step(fmu_instance *inst, double t_end)
{
    cvode_data *data = inst->solver;
    if (data->must_restart && restart(inst, data) != FMU_OK)
        return FMU_ERROR;
    int events = 0;
    for (;;) {
        sunrealtype t_reached = inst->time;
        if (CVodeSetStopTime(data->cvode, t_end) != CV_SUCCESS)
            return fmu_error(inst, "CVODE rejected the stop time %.17g", t_end);
        int flag = CVode(data->cvode, t_end, data->y, &t_reached, CV_NORMAL);
        if (flag < 0) {
            /* the integrator's state is unusable: restart from the last accepted point */
            data->must_restart = 1;
            return fmu_error(inst, "CVODE failed with flag %d between t = %.17g and %.17g", flag,
                             inst->time, t_end);
        }
        copy_state_out(inst, data);
        inst->time = t_reached;
        if (flag != CV_ROOT_RETURN)
            break;
        if (CVodeGetRootInfo(data->cvode, data->roots) != CV_SUCCESS)
            return fmu_error(inst, "CVODE could not report which event fired");
        for (size_t i = 0; i < inst->model->n_event_indicators; ++i)
            inst->fired[i] = data->roots[i] != 0;
        if (inst->importer_handles_events) {
            /* stop at the root; the importer applies the event in event mode */
            inst->event_pending = 1;
            return FMU_OK;
        }
        fmu_handle_events(inst, t_reached, inst->x);
        if (restart(inst, data) != FMU_OK)
            return FMU_ERROR;
        if (++events > MAX_EVENTS_PER_STEP)
            return fmu_error(inst, "more than %d internal events in one step at t = %.17g: "
                                   "the model chatters",
                             MAX_EVENTS_PER_STEP, t_reached);
        if (t_reached >= t_end)
            break;
    }
    inst->time = t_end;
    return FMU_OK;
}
