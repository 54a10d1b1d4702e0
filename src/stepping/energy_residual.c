#include "energy_residual.h"

#include <math.h>

#include "error.h"

/* The connection that drives input `input` of component `component`, or -1. */
static int driver(const ssx_system *sys, int component, int input)
{
    if (component < 0 || component >= sys->n_components || input < 0 ||
        input >= sys->components[component]->n_inputs) {
        return -2;
    }
    return sys->components[component]->input_driver[input];
}

static int check_end(ssx_system *sys, int bond, int component, int input, int other)
{
    int k = driver(sys, component, input);
    if (k == -2) {
        return fail_config(sys, -1, -1, sys->time,
                           "system '%s': power bond %d names component %d, input %d, which "
                           "does not exist",
                           sys->name, bond, component, input);
    }
    const ssx_component *c = sys->components[component];
    if (k < 0 || sys->connections[k].src_component != other) {
        return fail_config(sys, component, -1, sys->time,
                           "system '%s': power bond %d: input %d of '%s' must be connected "
                           "to an output of '%s', the bond's other side",
                           sys->name, bond, input, c->name, sys->components[other]->name);
    }
    const ssx_connection *cn = &sys->connections[k];
    if (c->input_ports[input].type != SSX_REAL ||
        sys->components[other]->output_ports[cn->src_output].type != SSX_REAL) {
        return fail_config(sys, component, -1, sys->time,
                           "system '%s': power bond %d: input %d of '%s' is not a Real "
                           "connection",
                           sys->name, bond, input, c->name);
    }
    return 0;
}

int energy_residual_check(ssx_system *sys)
{
    if (sys->n_power_bonds == 0) {
        return fail_config(sys, -1, -1, sys->time,
                           "system '%s': the energy step control needs at least one power bond",
                           sys->name);
    }
    for (int b = 0; b < sys->n_power_bonds; ++b) {
        const int *end = &sys->power_bonds[4 * b];
        if (end[0] == end[2] && end[0] >= 0) {
            return fail_config(sys, end[0], -1, sys->time,
                               "system '%s': power bond %d joins a component to itself",
                               sys->name, b);
        }
        if (check_end(sys, b, end[0], end[1], end[2]) != 0 ||
            check_end(sys, b, end[2], end[3], end[0]) != 0) {
            return -1;
        }
    }
    return 0;
}

/* What side `component` receives: its input times its output that drives the other input. */
static double side_power(const ssx_system *sys, int component, int input, int other,
                         int other_input)
{
    const ssx_connection *cn = &sys->connections[driver(sys, other, other_input)];
    const ssx_component *c = sys->components[component];
    return c->inputs[input] * c->outputs[cn->src_output];
}

double energy_residual_bond(const ssx_system *sys, int bond, double h)
{
    const ssx_step_control *sc = &sys->step_control;
    const int *end = &sys->power_bonds[4 * bond];
    double pa = side_power(sys, end[0], end[1], end[2], end[3]);
    double pb = side_power(sys, end[2], end[3], end[0], end[1]);
    double residual = fabs(pa - pb) * h;
    double level = fmax(fabs(pa), fabs(pb)) * h;
    return residual / (sc->atol + sc->rtol * level);
}

double energy_residual_error(const ssx_system *sys, double h, const double *measured)
{
    double sum = 0.0;
    for (int b = 0; b < sys->n_power_bonds; ++b) {
        double weighted = measured != NULL && !isnan(measured[b])
                              ? measured[b]
                              : energy_residual_bond(sys, b, h);
        sum += weighted * weighted;
    }
    return sys->n_power_bonds > 0 ? sqrt(sum / sys->n_power_bonds) : 0.0;
}
