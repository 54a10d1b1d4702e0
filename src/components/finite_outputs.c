/* Finite outputs (see finite_outputs.h). */
#include "finite_outputs.h"

#include <math.h>
#include <stdatomic.h>

#include "error.h"
#include "system.h"

void finite_outputs_watch(ssx_system *sys)
{
    atomic_store(&sys->non_finite_unfed, 0);
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        for (int k = 0; k < c->n_outputs; ++k) {
            c->output_watch[k] = (ssx_output_watch){.feeds = 0, .first_non_finite = NAN};
        }
    }
    for (int i = 0; i < sys->n_connections; ++i) {
        const ssx_connection *link = &sys->connections[i];
        sys->components[link->src_component]->output_watch[link->src_output].feeds = 1;
    }
}

int component_check_outputs(ssx_system *sys, ssx_component *c, double t)
{
    if (sys->allow_non_finite) {
        return 0;
    }
    for (int i = 0; i < c->n_outputs; ++i) {
        if (isfinite(c->outputs[i])) {
            continue;
        }
        /* before the first initialize nothing is known of the outputs: the initialize checks
         * them again */
        ssx_output_watch *watch = c->output_watch;
        if (watch == NULL) {
            continue;
        }
        if (watch[i].feeds) {
            return fail_non_finite(sys, c, i, t);
        }
        if (isnan(watch[i].first_non_finite)) {
            watch[i].first_non_finite = t;
            atomic_fetch_add(&sys->non_finite_unfed, 1);
        }
    }
    return 0;
}

int ssx_non_finite_outputs(const ssx_system *sys, int *components, int *outputs, double *times,
                           int max)
{
    if (max <= 0) {
        return atomic_load(&sys->non_finite_unfed);
    }
    int n = 0;
    for (int i = 0; i < sys->n_components; ++i) {
        const ssx_component *c = sys->components[i];
        for (int k = 0; k < c->n_outputs && c->output_watch != NULL; ++k) {
            double first = c->output_watch[k].first_non_finite;
            if (isnan(first)) {
                continue;
            }
            if (n < max) {
                components[n] = i;
                outputs[n] = k;
                times[n] = first;
            }
            ++n;
        }
    }
    return n;
}
