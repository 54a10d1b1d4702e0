/* The whole system's state by handle (ssx_state_*): each component's own state through its
 * kind (component_state_ops), and the engine's values beside it. Serialized: a header (magic,
 * version, layout digest), the layout itself (to name what differs on another system), then
 * the values in the order the state holds them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "algorithm.h"
#include "byte_stream.h"
#include "component.h"
#include "error.h"
#include "indicator.h"
#include "input_order.h"
#include "own_events.h"
#include "recording.h"
#include "system.h"

static const char MAGIC[8] = {'S', 'S', 'X', 'S', 'T', 'A', 'T', 'E'};
enum { FORMAT_VERSION = 1 };

struct ssx_system_state {
    int n_components;
    void **component_states; /* per component: its kind's state, NULL when it holds none */
    const component_state_ops **kinds; /* per component, to free its state */
    double *ports; /* every component's inputs, then its outputs, in component order */
    size_t n_ports;
    indicator_state *indicators;
    int n_indicators;
    double *motion; /* the input motion (input_order.h) */
    size_t n_motion;
    double carried[ALGORITHM_CARRIED];
    double time;
    execution_grid grid;
    ssx_statistics stats;
    ssx_termination termination;
};

/* Why component c cannot give its state by handle; NULL when it can. */
static const char *cannot_save(const ssx_component *c)
{
    if (c->ops->saved_state == NULL) {
        return "a Python component keeps its state in Python";
    }
    if (c->hooks.snapshot != NULL || c->hooks.restore != NULL) {
        return "its state is saved by Python hooks";
    }
    if (c->ops->saved_state->save != NULL && !c->can_snapshot) {
        return "its FMU does not declare canGetAndSetFMUstate";
    }
    return NULL;
}

static size_t port_count(const ssx_system *sys)
{
    size_t n = 0;
    for (int i = 0; i < sys->n_components; ++i) {
        n += (size_t)sys->components[i]->n_inputs + (size_t)sys->components[i]->n_outputs;
    }
    return n;
}

void ssx_state_free(ssx_system_state *state)
{
    if (state == NULL) {
        return;
    }
    for (int i = 0; state->component_states != NULL && i < state->n_components; ++i) {
        if (state->component_states[i] != NULL) {
            state->kinds[i]->free(state->component_states[i]);
        }
    }
    free(state->component_states);
    free(state->kinds);
    free(state->ports);
    free(state->indicators);
    free(state->motion);
    free(state);
}

/* A state of the system's shape with nothing in it yet; NULL with the error set. */
static ssx_system_state *state_new(ssx_system *sys)
{
    ssx_system_state *state = calloc(1, sizeof *state);
    size_t n_components = (size_t)sys->n_components + 1;
    if (state != NULL) {
        state->n_components = sys->n_components;
        state->n_indicators = sys->n_indicators;
        state->n_ports = port_count(sys);
        state->n_motion = input_order_state_size(sys);
        state->component_states = calloc(n_components, sizeof *state->component_states);
        state->kinds = calloc(n_components, sizeof *state->kinds);
        state->ports = malloc((state->n_ports + 1) * sizeof *state->ports);
        state->indicators = malloc(((size_t)sys->n_indicators + 1) * sizeof *state->indicators);
        state->motion = malloc((state->n_motion + 1) * sizeof *state->motion);
    }
    if (state == NULL || state->component_states == NULL || state->kinds == NULL ||
        state->ports == NULL || state->indicators == NULL || state->motion == NULL) {
        ssx_state_free(state);
        fail(sys, -1, -1, sys->time, "out of memory saving the state of system '%s'", sys->name);
        return NULL;
    }
    for (int i = 0; i < sys->n_components; ++i) {
        state->kinds[i] = sys->components[i]->ops->saved_state;
    }
    return state;
}

/* The engine's values into the state. */
static void save_engine(const ssx_system *sys, ssx_system_state *state)
{
    double *port = state->ports;
    for (int i = 0; i < sys->n_components; ++i) {
        const ssx_component *c = sys->components[i];
        memcpy(port, c->inputs, (size_t)c->n_inputs * sizeof(double));
        port += c->n_inputs;
        memcpy(port, c->outputs, (size_t)c->n_outputs * sizeof(double));
        port += c->n_outputs;
    }
    if (sys->n_indicators > 0) {
        memcpy(state->indicators, sys->indicator_states,
               (size_t)sys->n_indicators * sizeof *state->indicators);
    }
    input_order_state_save(sys, state->motion);
    memset(state->carried, 0, sizeof state->carried);
    if (sys->algorithm->carry_out != NULL) {
        sys->algorithm->carry_out(sys, state->carried);
    }
    state->time = sys->time;
    state->grid = sys->grid;
    state->stats = sys->stats;
    state->termination = sys->termination;
}

static int check_ready(ssx_system *sys, const char *what)
{
    if (!sys->initialized || sys->algorithm == NULL) {
        return fail_config(sys, -1, -1, sys->time,
                           "system '%s' is not initialized: no state to %s", sys->name, what);
    }
    for (int i = 0; i < sys->n_components; ++i) {
        const char *why = cannot_save(sys->components[i]);
        if (why != NULL) {
            return fail_config(sys, i, -1, sys->time,
                               "component '%s' cannot %s its state by handle: %s",
                               sys->components[i]->name, what, why);
        }
    }
    return 0;
}

ssx_system_state *ssx_state_save(ssx_system *sys)
{
    clear_error(sys);
    if (check_ready(sys, "save") != 0) {
        return NULL;
    }
    ssx_system_state *state = state_new(sys);
    if (state == NULL) {
        return NULL;
    }
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        if (state->kinds[i]->save == NULL) {
            continue;
        }
        state->component_states[i] = state->kinds[i]->save(sys, c);
        if (state->component_states[i] == NULL) {
            ssx_state_free(state);
            return NULL;
        }
    }
    save_engine(sys, state);
    return state;
}

/* The state fits the system as it is now built (a state of another system, or of this one
 * before it was changed, does not). */
static int check_fits(ssx_system *sys, const ssx_system_state *state)
{
    if (state->n_components != sys->n_components || state->n_indicators != sys->n_indicators ||
        state->n_ports != port_count(sys) || state->n_motion != input_order_state_size(sys)) {
        return fail_config(sys, -1, -1, sys->time,
                           "system '%s': the state was saved from a system of another layout "
                           "(%d components, %d indicators, %zu ports; this one has %d, %d, %zu)",
                           sys->name, state->n_components, state->n_indicators, state->n_ports,
                           sys->n_components, sys->n_indicators, port_count(sys));
    }
    for (int i = 0; i < sys->n_components; ++i) {
        if (state->kinds[i] != sys->components[i]->ops->saved_state) {
            return fail_config(sys, i, -1, sys->time,
                               "system '%s': component %d ('%s') is of another kind than in "
                               "the state",
                               sys->name, i, sys->components[i]->name);
        }
    }
    return 0;
}

int ssx_state_restore(ssx_system *sys, const ssx_system_state *state)
{
    clear_error(sys);
    if (state == NULL) {
        return fail_config(sys, -1, -1, sys->time, "system '%s': no state to restore",
                           sys->name);
    }
    if (check_ready(sys, "restore") != 0 || check_fits(sys, state) != 0) {
        return -1;
    }
    /* the components first: a restore that fails leaves the engine's values as they were */
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        if (state->kinds[i]->restore != NULL &&
            state->kinds[i]->restore(sys, c, state->component_states[i], state->time) != 0) {
            return -1;
        }
    }
    const double *port = state->ports;
    for (int i = 0; i < sys->n_components; ++i) {
        ssx_component *c = sys->components[i];
        memcpy(c->inputs, port, (size_t)c->n_inputs * sizeof(double));
        port += c->n_inputs;
        memcpy(c->outputs, port, (size_t)c->n_outputs * sizeof(double));
        port += c->n_outputs;
    }
    if (sys->n_indicators > 0) {
        memcpy(sys->indicator_states, state->indicators,
               (size_t)sys->n_indicators * sizeof *state->indicators);
    }
    input_order_state_restore(sys, state->motion);
    if (sys->algorithm->carry_in != NULL) {
        sys->algorithm->carry_in(sys, state->carried);
    }
    /* saved between steps, where every own event was committed */
    own_events_clear(sys);
    sys->time = state->time;
    sys->grid = state->grid;
    sys->stats = state->stats;
    sys->termination = state->termination;
    /* observers learn that the samples since state->time were left behind */
    return record_state_restored(sys, state->time);
}

/* ------------------------------------------------------------------ bytes */

/* What a serialized state must match: per component its name, kind, ports (type and value
 * reference), then the indicators and the input motion's size. */
static void write_layout(const ssx_system *sys, byte_writer *w)
{
    write_u64(w, (uint64_t)sys->n_components);
    for (int i = 0; i < sys->n_components; ++i) {
        const ssx_component *c = sys->components[i];
        size_t name_length = strlen(c->name);
        write_u64(w, name_length);
        write_bytes(w, c->name, name_length);
        write_u64(w, c->ops->saved_state == &component_no_saved_state ? 0 : 1);
        write_u64(w, (uint64_t)c->n_inputs);
        write_u64(w, (uint64_t)c->n_outputs);
        write_bytes(w, c->input_ports, (size_t)c->n_inputs * sizeof *c->input_ports);
        write_bytes(w, c->output_ports, (size_t)c->n_outputs * sizeof *c->output_ports);
    }
    write_u64(w, (uint64_t)sys->n_indicators);
    for (int i = 0; i < sys->n_indicators; ++i) {
        write_u64(w, (uint64_t)(sys->indicators[i].component + 1));
        write_u64(w, (uint64_t)(sys->indicators[i].output + 1));
    }
    write_u64(w, input_order_state_size(sys));
}

/* FNV-1a, 64 bits: the layout's digest, the first thing compared. */
static uint64_t digest_of(const unsigned char *bytes, size_t n)
{
    uint64_t h = 14695981039346656037ULL;
    for (size_t i = 0; i < n; ++i) {
        h = (h ^ bytes[i]) * 1099511628211ULL;
    }
    return h;
}

static int out_of_memory(ssx_system *sys)
{
    return fail(sys, -1, -1, sys->time, "out of memory serializing the state of system '%s'",
                sys->name);
}

int ssx_state_serialize(ssx_system *sys, const ssx_system_state *state, unsigned char **bytes,
                        size_t *size)
{
    clear_error(sys);
    if (bytes == NULL || size == NULL || state == NULL) {
        return fail_config(sys, -1, -1, sys->time, "system '%s': nothing to serialize into",
                           sys->name);
    }
    *bytes = NULL;
    *size = 0;
    if (check_ready(sys, "serialize") != 0 || check_fits(sys, state) != 0) {
        return -1;
    }
    for (int i = 0; i < sys->n_components; ++i) {
        const ssx_component *c = sys->components[i];
        for (int k = 0; k < c->n_inputs + c->n_outputs; ++k) {
            const ssx_port *port =
                k < c->n_inputs ? &c->input_ports[k] : &c->output_ports[k - c->n_inputs];
            if (port->type == SSX_STRING || port->type == SSX_BINARY) {
                return fail_config(sys, i, -1, sys->time,
                                   "component '%s' has a String or Binary port: its values "
                                   "are numbers of this system's text table, which a "
                                   "serialized state does not carry",
                                   c->name);
            }
        }
    }
    byte_writer layout = {0};
    write_layout(sys, &layout);
    byte_writer w = {0};
    write_bytes(&w, MAGIC, sizeof MAGIC);
    write_u64(&w, FORMAT_VERSION);
    write_u64(&w, digest_of(layout.bytes, layout.size));
    write_u64(&w, layout.size);
    write_bytes(&w, layout.bytes, layout.size);
    free(layout.bytes);
    if (layout.failed) {
        w.failed = 1;
    }
    for (int i = 0; i < sys->n_components; ++i) {
        if (state->kinds[i]->serialize != NULL &&
            state->kinds[i]->serialize(sys, sys->components[i], state->component_states[i],
                                       &w) != 0) {
            free(w.bytes);
            return -1;
        }
    }
    write_doubles(&w, state->ports, state->n_ports);
    write_bytes(&w, state->indicators, (size_t)state->n_indicators * sizeof *state->indicators);
    write_doubles(&w, state->motion, state->n_motion);
    write_doubles(&w, state->carried, ALGORITHM_CARRIED);
    write_doubles(&w, &state->time, 1);
    write_bytes(&w, &state->grid, sizeof state->grid);
    write_bytes(&w, &state->stats, sizeof state->stats);
    write_bytes(&w, &state->termination, sizeof state->termination);
    if (w.failed) {
        free(w.bytes);
        return out_of_memory(sys);
    }
    *bytes = w.bytes;
    *size = w.size;
    return 0;
}

void ssx_state_bytes_free(unsigned char *bytes)
{
    free(bytes);
}

/* The bytes' layout against this system's: names the first difference. */
static int refuse_layout(ssx_system *sys, byte_reader *theirs)
{
    uint64_t n = read_u64(theirs);
    if (n != (uint64_t)sys->n_components) {
        return fail_config(sys, -1, -1, sys->time,
                           "the state holds %llu components' states; system '%s' has %d "
                           "components",
                           (unsigned long long)n, sys->name, sys->n_components);
    }
    for (int i = 0; i < sys->n_components; ++i) {
        const ssx_component *c = sys->components[i];
        uint64_t name_length = read_u64(theirs);
        const unsigned char *name =
            name_length <= theirs->size ? read_span(theirs, (size_t)name_length) : NULL;
        if (name == NULL || name_length != strlen(c->name) ||
            memcmp(name, c->name, (size_t)name_length) != 0) {
            return fail_config(sys, i, -1, sys->time,
                               "the state's component %d is not '%s' of system '%s' (it is "
                               "'%.*s')",
                               i, c->name, sys->name, name != NULL ? (int)name_length : 0,
                               name != NULL ? (const char *)name : "");
        }
        uint64_t kind = read_u64(theirs);
        uint64_t n_inputs = read_u64(theirs);
        uint64_t n_outputs = read_u64(theirs);
        if (kind != (c->ops->saved_state == &component_no_saved_state ? 0U : 1U) ||
            n_inputs != (uint64_t)c->n_inputs || n_outputs != (uint64_t)c->n_outputs) {
            return fail_config(sys, i, -1, sys->time,
                               "component '%s': in the state it is of another kind or has "
                               "%llu inputs and %llu outputs (here %d and %d)",
                               c->name, (unsigned long long)n_inputs,
                               (unsigned long long)n_outputs, c->n_inputs, c->n_outputs);
        }
        const unsigned char *inputs = read_span(theirs, (size_t)n_inputs * sizeof(ssx_port));
        const unsigned char *outputs = read_span(theirs, (size_t)n_outputs * sizeof(ssx_port));
        if (inputs == NULL || outputs == NULL ||
            memcmp(inputs, c->input_ports, (size_t)n_inputs * sizeof(ssx_port)) != 0 ||
            memcmp(outputs, c->output_ports, (size_t)n_outputs * sizeof(ssx_port)) != 0) {
            return fail_config(sys, i, -1, sys->time,
                               "component '%s': its ports (types, value references) differ "
                               "from the state's",
                               c->name);
        }
    }
    if (read_u64(theirs) != (uint64_t)sys->n_indicators) {
        return fail_config(sys, -1, -1, sys->time,
                           "the state's event indicators differ from system '%s''s %d",
                           sys->name, sys->n_indicators);
    }
    return fail_config(sys, -1, -1, sys->time,
                       "the state's event indicators or input motion differ from system '%s''s",
                       sys->name);
}

ssx_system_state *ssx_state_deserialize(ssx_system *sys, const unsigned char *bytes,
                                        size_t size)
{
    clear_error(sys);
    if (check_ready(sys, "deserialize") != 0) {
        return NULL;
    }
    byte_reader r = {.bytes = bytes, .size = bytes != NULL ? size : 0};
    const unsigned char *magic = read_span(&r, sizeof MAGIC);
    if (magic == NULL || memcmp(magic, MAGIC, sizeof MAGIC) != 0) {
        fail_config(sys, -1, -1, sys->time,
                    "system '%s': the bytes are not a serialized syssimx system state",
                    sys->name);
        return NULL;
    }
    uint64_t version = read_u64(&r);
    if (version != FORMAT_VERSION) {
        fail_config(sys, -1, -1, sys->time,
                    "system '%s': the state is of format version %llu; this engine reads %d",
                    sys->name, (unsigned long long)version, FORMAT_VERSION);
        return NULL;
    }
    uint64_t digest = read_u64(&r);
    uint64_t layout_size = read_u64(&r);
    const unsigned char *layout =
        layout_size <= size ? read_span(&r, (size_t)layout_size) : NULL;
    byte_writer ours = {0};
    write_layout(sys, &ours);
    if (ours.failed) {
        free(ours.bytes);
        out_of_memory(sys);
        return NULL;
    }
    int same = layout != NULL && digest == digest_of(ours.bytes, ours.size) &&
               layout_size == ours.size && memcmp(layout, ours.bytes, ours.size) == 0;
    free(ours.bytes);
    if (!same) {
        byte_reader theirs = {.bytes = layout, .size = layout != NULL ? (size_t)layout_size : 0};
        refuse_layout(sys, &theirs);
        return NULL;
    }
    ssx_system_state *state = state_new(sys);
    if (state == NULL) {
        return NULL;
    }
    for (int i = 0; i < sys->n_components; ++i) {
        if (state->kinds[i]->deserialize == NULL) {
            continue;
        }
        state->component_states[i] = state->kinds[i]->deserialize(sys, sys->components[i], &r);
        if (state->component_states[i] == NULL) {
            ssx_state_free(state);
            return NULL;
        }
    }
    read_doubles(&r, state->ports, state->n_ports);
    read_bytes(&r, state->indicators, (size_t)state->n_indicators * sizeof *state->indicators);
    read_doubles(&r, state->motion, state->n_motion);
    read_doubles(&r, state->carried, ALGORITHM_CARRIED);
    read_doubles(&r, &state->time, 1);
    read_bytes(&r, &state->grid, sizeof state->grid);
    read_bytes(&r, &state->stats, sizeof state->stats);
    read_bytes(&r, &state->termination, sizeof state->termination);
    if (r.failed || r.at != r.size || !isfinite(state->time)) {
        ssx_state_free(state);
        fail_config(sys, -1, -1, sys->time,
                    "system '%s': the serialized state is cut short or has bytes beyond its "
                    "end",
                    sys->name);
        return NULL;
    }
    return state;
}
