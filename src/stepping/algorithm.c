/* The table of master algorithms. */
#include "algorithm.h"

#include "adaptive.h"
#include "coupling.h"
#include "hybrid.h"
#include "event_source.h"
#include "recording.h"
#include "system.h"

/* No events: one coupled step per communication step. */
static int plain_step(ssx_system *sys, double t, double from, double t_next, int *event)
{
    (void)t;
    *event = 0;
    if (coupling_step(sys, from, t_next - from) != 0 ||
        event_sources_commit_own(sys, t_next) != 0) {
        return -1;
    }
    sys->stats.macro_steps++;
    sys->time = t_next;
    return record_grid_point(sys, t_next);
}

enum { PLAIN, HYBRID, ADAPTIVE };

static const ssx_master_algorithm ALGORITHMS[] = {
    [PLAIN] = {NULL, plain_step, NULL, NULL, NULL},
    [HYBRID] = {hybrid_prepare, hybrid_step, hybrid_release, hybrid_carry_out, hybrid_carry_in},
    /* events inside adaptive steps too: its workspace is the hybrid one */
    [ADAPTIVE] = {adaptive_prepare, adaptive_step, adaptive_release, adaptive_carry_out,
                  adaptive_carry_in},
};

void master_algorithm_release(ssx_system *sys)
{
    if (sys->algorithm != NULL && sys->algorithm->release != NULL) {
        sys->algorithm->release(sys, sys->algorithm_workspace);
    }
    sys->algorithm = NULL;
    sys->algorithm_workspace = NULL;
}

int master_algorithm_choose(ssx_system *sys)
{
    master_algorithm_release(sys);
    int chosen = sys->step_control.enabled ? ADAPTIVE : sys->stepping_hybrid ? HYBRID : PLAIN;
    const ssx_master_algorithm *algorithm = &ALGORITHMS[chosen];
    sys->algorithm = algorithm;
    return algorithm->prepare != NULL ? algorithm->prepare(sys, &sys->algorithm_workspace) : 0;
}
