#include "fmu_guid.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "fmu_solver.h"
#include "model.h"

/* FNV-1a, 64 bit: small, deterministic, good enough to tell two tables apart. */
static uint64_t hash_bytes(uint64_t hash, const void *data, size_t size)
{
    const unsigned char *bytes = data;
    for (size_t i = 0; i < size; ++i) {
        hash ^= bytes[i];
        hash *= 1099511628211ull;
    }
    return hash;
}

static uint64_t hash_text(uint64_t hash, const char *text)
{
    return text ? hash_bytes(hash, text, strlen(text) + 1) : hash_bytes(hash, "", 1);
}

static uint64_t hash_variables(uint64_t hash, const model_variable *vars, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        const model_variable *v = &vars[i];
        int fields[] = {(int)v->vr, v->type, v->causality, v->variability, v->initial,
                        v->derivative_of};
        hash = hash_text(hash, v->name);
        hash = hash_text(hash, v->unit);
        hash = hash_bytes(hash, fields, sizeof fields);
        hash = hash_bytes(hash, &v->start, sizeof v->start);
    }
    return hash;
}

static uint64_t hash_definition(uint64_t seed)
{
    uint64_t hash = hash_text(seed, fmu_model.name);
    hash = hash_text(hash, fmu_solver_name);
    hash = hash_variables(hash, fmu_model.variables, fmu_model.n_variables);
    return hash_variables(hash, fmu_solver_variables, fmu_solver_variable_count);
}

void fmu_guid(char guid[FMU_GUID_LENGTH])
{
    uint64_t high = hash_definition(14695981039346656037ull);
    uint64_t low = hash_definition(high);
    snprintf(guid, FMU_GUID_LENGTH, "{%08x-%04x-%04x-%04x-%012llx}", (unsigned)(high >> 32),
             (unsigned)((high >> 16) & 0xffffu), (unsigned)(high & 0xffffu),
             (unsigned)(low >> 48), (unsigned long long)(low & 0xffffffffffffull));
}
