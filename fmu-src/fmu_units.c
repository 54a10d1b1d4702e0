#include "fmu_units.h"

#include <stddef.h>
#include <string.h>

static const unit_definition units[] = {
    {"s", 0, 0, 1, 0, 1},          {"1/s", 0, 0, -1, 0, 1},       {"kg", 1, 0, 0, 0, 1},
    {"m", 0, 1, 0, 0, 1},          {"cm", 0, 1, 0, 0, 0.01},      {"m/s", 0, 1, -1, 0, 1},
    {"m/s2", 0, 1, -2, 0, 1},      {"rad", 0, 0, 0, 1, 1},        {"rad/s", 0, 0, -1, 1, 1},
    {"rad/s2", 0, 0, -2, 1, 1},    {"kg.m2", 1, 2, 0, 0, 1},      {"N.m", 1, 2, -2, 0, 1},
    {"N.m/rad", 1, 2, -2, -1, 1},  {"N.m.s/rad", 1, 2, -1, -1, 1}, {"-", 0, 0, 0, 0, 1},
};

const unit_definition *fmu_unit(const char *name)
{
    for (size_t i = 0; i < sizeof units / sizeof *units; ++i)
        if (name != NULL && strcmp(units[i].name, name) == 0)
            return &units[i];
    return NULL;
}
